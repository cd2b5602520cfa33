// What a physical device is and what it can do: the DeviceInfo the CLI prints, the
// capabilities a pipeline may ask for, and the choice of a device from --device.
#pragma once

#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk_reference/vk_reference.hpp"

namespace rastercmp::vk {

// Optional features and extensions the reference can use (lavapipe has them all).
struct DeviceCapabilities {
  uint32_t api_version = 0;
  VkPhysicalDeviceFeatures core{};
  VkPhysicalDeviceLimits limits{};
  bool line_rasterization_ext = false;  // VK_EXT_line_rasterization
  bool rectangular_lines = false, bresenham_lines = false, smooth_lines = false;
  bool depth_clip_enable_ext = false;  // VK_EXT_depth_clip_enable
  bool depth_clip_enable = false;      // its depthClipEnable feature
};

bool has_device_extension(VkPhysicalDevice device, const char* name);

DeviceCapabilities query_capabilities(VkPhysicalDevice device);

DeviceInfo describe_device(VkPhysicalDevice device, uint32_t index);

// "0: llvmpipe (...) [cpu]; 1: ..." for error messages.
std::string format_device_list(const std::vector<DeviceInfo>& devices);

// The device `selector` names: empty → the first whose name contains "llvmpipe"; all digits →
// that index; otherwise the first whose name contains it (case-insensitive).
// Throws EnvironmentError listing the devices when none matches.
uint32_t choose_device(const std::vector<DeviceInfo>& devices, const std::string& selector);

}  // namespace rastercmp::vk
