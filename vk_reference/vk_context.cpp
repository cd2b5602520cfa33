#include "vk_reference/vk_context.hpp"

#include <fmt/core.h>

#include "model/errors.hpp"
#include "vk_reference/vk_check.hpp"
#include "vk_reference/vk_loader.hpp"

namespace rastercmp::vk {
namespace {

uint32_t graphics_compute_family(VkPhysicalDevice device, const std::string& name) {
  uint32_t count = 0;
  api().vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  api().vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  constexpr VkQueueFlags kNeeded = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & kNeeded) == kNeeded) return i;
  }
  throw NotSupportedError(name + " has no queue family with both graphics and compute");
}

// Keeps only what the reference uses: geometryShader (gl_PrimitiveID in the fragment shader) is
// required; the rest is enabled when present and checked per pipeline (vk_pipeline.cpp).
DeviceCapabilities features_to_enable(const DeviceCapabilities& supported, const std::string& name) {
  if (supported.api_version < VK_API_VERSION_1_1) {
    throw NotSupportedError(name + " supports only Vulkan 1.0; the reference needs Vulkan 1.1");
  }
  if (!supported.core.geometryShader) {
    throw NotSupportedError(name +
                            " lacks the geometryShader feature (needed for gl_PrimitiveID in the fragment shader)");
  }
  DeviceCapabilities enabled = supported;
  enabled.core = VkPhysicalDeviceFeatures{};
  enabled.core.geometryShader = VK_TRUE;
  enabled.core.fillModeNonSolid = supported.core.fillModeNonSolid;
  enabled.core.wideLines = supported.core.wideLines;
  enabled.core.depthBiasClamp = supported.core.depthBiasClamp;
  enabled.core.depthClamp = supported.core.depthClamp;
  // VK_EXT_depth_range_unrestricted stays off: it would stop lavapipe clamping depth to [0,1]
  // for D32_SFLOAT (docs/lavapipe-rules.md §3.4, Test configuration §1).
  return enabled;
}

}  // namespace

Context::Context(const VkOptions& options) : instance_(options.validate) {
  const std::vector<VkPhysicalDevice> devices = instance_.physical_devices();
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe_device(devices[i], i));
  const uint32_t chosen = choose_device(infos, options.device);
  physical_device_ = devices[chosen];
  info_ = infos[chosen];
  enabled_ = features_to_enable(query_capabilities(physical_device_), info_.name);
  api().vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_);
  queue_family_ = graphics_compute_family(physical_device_, info_.name);
  create_device();
}

void Context::create_device() {
  std::vector<const char*> extensions;
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features.features = enabled_.core;
  VkPhysicalDeviceLineRasterizationFeaturesEXT line{};
  line.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT;
  if (enabled_.line_rasterization_ext) {
    extensions.push_back(VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME);
    line.rectangularLines = enabled_.rectangular_lines;
    line.bresenhamLines = enabled_.bresenham_lines;
    line.smoothLines = enabled_.smooth_lines;
    line.pNext = features.pNext;
    features.pNext = &line;
  }
  VkPhysicalDeviceDepthClipEnableFeaturesEXT depth_clip{};
  depth_clip.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_ENABLE_FEATURES_EXT;
  if (enabled_.depth_clip_enable_ext) {
    extensions.push_back(VK_EXT_DEPTH_CLIP_ENABLE_EXTENSION_NAME);
    depth_clip.depthClipEnable = enabled_.depth_clip_enable;
    depth_clip.pNext = features.pNext;
    features.pNext = &depth_clip;
  }
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  info.pNext = &features;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkDevice device = VK_NULL_HANDLE;
  check(api().vkCreateDevice(physical_device_, &info, nullptr, &device), "vkCreateDevice");
  device_ = Owned<VkDevice>(device, [](VkDevice h) { api().vkDestroyDevice(h, nullptr); });
  api().vkGetDeviceQueue(device, queue_family_, 0, &queue_);

  VkCommandPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.queueFamilyIndex = queue_family_;
  VkCommandPool pool = VK_NULL_HANDLE;
  check(api().vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
  command_pool_ = own(device, api().vkDestroyCommandPool, pool);
}

uint32_t Context::memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    const bool allowed = type_bits & (1u << i);
    if (allowed && (memory_.memoryTypes[i].propertyFlags & required) == required) return i;
  }
  throw NotSupportedError(
      fmt::format("{} has no memory type with properties {:#x} among types {:#x}", info_.name, required, type_bits));
}

}  // namespace rastercmp::vk
