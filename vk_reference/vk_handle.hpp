// Owned<Handle>: a move-only owner of one Vulkan handle and the call that destroys it.
// Every handle the reference creates lives in one of these (docs/lavapipe-rules.md Test
// configuration §1 wants a harness that cannot leak or double-destroy on an error path).
#pragma once

#include <functional>
#include <utility>

#include <vulkan/vulkan.h>

namespace rastercmp::vk {

template <typename Handle>
class Owned {
 public:
  Owned() = default;
  Owned(Handle handle, std::function<void(Handle)> destroy) : handle_(handle), destroy_(std::move(destroy)) {}
  ~Owned() { reset(); }

  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  Owned(Owned&& other) noexcept
      : handle_(std::exchange(other.handle_, VK_NULL_HANDLE)), destroy_(std::move(other.destroy_)) {}
  Owned& operator=(Owned&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
      destroy_ = std::move(other.destroy_);
    }
    return *this;
  }

  Handle get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

  void reset() {
    if (handle_ != VK_NULL_HANDLE && destroy_) destroy_(handle_);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  Handle handle_ = VK_NULL_HANDLE;
  std::function<void(Handle)> destroy_;
};

// Owns a handle created from `device` and destroyed by vkDestroyX(device, handle, nullptr).
template <typename Handle>
Owned<Handle> own(VkDevice device, void (*destroy)(VkDevice, Handle, const VkAllocationCallbacks*), Handle handle) {
  return Owned<Handle>(handle, [device, destroy](Handle h) { destroy(device, h, nullptr); });
}

}  // namespace rastercmp::vk
