// The Vulkan instance, optionally with the Khronos validation layer and a debug-utils messenger
// that collects its warnings and errors (CTS --deqp-vk-validation analogue).
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk_reference/vk_handle.hpp"
#include "vk_reference/vk_loader.hpp"

namespace rastercmp::vk {

// Messages the validation layer reported (severity warning or error), in arrival order.
struct MessageLog {
  std::mutex mutex;
  std::vector<std::string> messages;
};

class Instance {
 public:
  // Throws EnvironmentError: no loader/driver, or validate without the validation layer.
  explicit Instance(bool validate);

  VkInstance get() const { return instance_.get(); }
  const std::vector<std::string>& messages() const { return log_->messages; }

  // Every physical device the loader reports, in its order (the order `--device N` indexes).
  std::vector<VkPhysicalDevice> physical_devices() const;

 private:
  std::unique_ptr<MessageLog> log_ = std::make_unique<MessageLog>();  // the messenger points here
  Owned<VkInstance> instance_;
  Owned<VkDebugUtilsMessengerEXT> messenger_;
};

}  // namespace rastercmp::vk
