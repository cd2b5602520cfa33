// The instance, the chosen physical device and the logical device, created once per
// VulkanRenderer and reused for every scene: queue, command pool, memory-type lookup.
#pragma once

#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk_reference/vk_device_info.hpp"
#include "vk_reference/vk_handle.hpp"
#include "vk_reference/vk_instance.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::vk {

class Context {
 public:
  // Throws EnvironmentError (no driver / device / layer), NotSupportedError (device lacks
  // geometryShader, Vulkan 1.1 or a graphics+compute queue).
  explicit Context(const VkOptions& options);

  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_.get(); }
  VkQueue queue() const { return queue_; }
  VkCommandPool command_pool() const { return command_pool_.get(); }
  const DeviceInfo& info() const { return info_; }
  // The features and extensions enabled on the logical device (a subset of the device's).
  const DeviceCapabilities& enabled() const { return enabled_; }
  const std::vector<std::string>& validation_messages() const { return instance_.messages(); }

  // Index of a memory type allowed by `type_bits` with all of `required`. Throws NotSupportedError.
  uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const;

 private:
  void create_device();

  Instance instance_;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  DeviceInfo info_;
  DeviceCapabilities enabled_;
  VkPhysicalDeviceMemoryProperties memory_{};
  uint32_t queue_family_ = 0;
  Owned<VkDevice> device_;
  VkQueue queue_ = VK_NULL_HANDLE;
  Owned<VkCommandPool> command_pool_;
};

}  // namespace rastercmp::vk
