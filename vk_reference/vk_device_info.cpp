#include "vk_reference/vk_device_info.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>

#include <fmt/core.h>

#include "model/depth_format.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "vk_reference/vk_check.hpp"
#include "vk_reference/vk_translate.hpp"

namespace rastercmp::vk {
namespace {

const char* device_type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

std::string version_string(uint32_t version) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                     VK_API_VERSION_PATCH(version));
}

bool driver_properties_available(VkPhysicalDevice device, uint32_t api_version) {
  return api_version >= VK_API_VERSION_1_2 || has_device_extension(device, VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME);
}

std::vector<DepthFormat> renderable_depth_formats(VkPhysicalDevice device) {
  std::vector<DepthFormat> formats;
  for (DepthFormat format : kDepthFormats) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(device, to_vk_format(format), &properties);
    if (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) {
      formats.push_back(format);
    }
  }
  return formats;
}

std::vector<uint32_t> sample_count_list(VkSampleCountFlags flags) {
  std::vector<uint32_t> counts;
  for (uint32_t count = 1; count <= 64; count *= 2) {
    if (flags & count) counts.push_back(count);  // VkSampleCountFlagBits value == count
  }
  return counts;
}

bool contains_ignoring_case(const std::string& text, const std::string& part) {
  auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
  };
  return lower(text).find(lower(part)) != std::string::npos;
}

}  // namespace

bool has_device_extension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr), "vkEnumerateDeviceExtensionProperties");
  std::vector<VkExtensionProperties> extensions(count);
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()),
        "vkEnumerateDeviceExtensionProperties");
  return std::any_of(extensions.begin(), extensions.end(),
                     [name](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

DeviceCapabilities query_capabilities(VkPhysicalDevice device) {
  DeviceCapabilities caps;
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device, &properties);
  caps.api_version = properties.apiVersion;
  caps.limits = properties.limits;
  caps.line_rasterization_ext = has_device_extension(device, VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME);
  caps.depth_clip_enable_ext = has_device_extension(device, VK_EXT_DEPTH_CLIP_ENABLE_EXTENSION_NAME);

  VkPhysicalDeviceLineRasterizationFeaturesEXT line{};
  line.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT;
  VkPhysicalDeviceDepthClipEnableFeaturesEXT depth_clip{};
  depth_clip.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_ENABLE_FEATURES_EXT;
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  if (caps.line_rasterization_ext) {
    line.pNext = features.pNext;
    features.pNext = &line;
  }
  if (caps.depth_clip_enable_ext) {
    depth_clip.pNext = features.pNext;
    features.pNext = &depth_clip;
  }
  vkGetPhysicalDeviceFeatures2(device, &features);
  caps.core = features.features;
  caps.rectangular_lines = line.rectangularLines;
  caps.bresenham_lines = line.bresenhamLines;
  caps.smooth_lines = line.smoothLines;
  caps.depth_clip_enable = depth_clip.depthClipEnable;
  return caps;
}

DeviceInfo describe_device(VkPhysicalDevice device, uint32_t index) {
  VkPhysicalDeviceDriverProperties driver{};
  driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
  VkPhysicalDeviceProperties2 properties{};
  properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  VkPhysicalDeviceProperties basic{};
  vkGetPhysicalDeviceProperties(device, &basic);
  const bool has_driver = driver_properties_available(device, basic.apiVersion);
  if (has_driver) properties.pNext = &driver;
  vkGetPhysicalDeviceProperties2(device, &properties);
  const VkPhysicalDeviceProperties& p = properties.properties;

  DeviceInfo info;
  info.index = index;
  info.name = p.deviceName;
  info.type = device_type_name(p.deviceType);
  if (has_driver) {
    info.driver_name = driver.driverName;
    info.driver_info = driver.driverInfo;
  }
  info.api_version = version_string(p.apiVersion);
  info.sub_pixel_precision_bits = p.limits.subPixelPrecisionBits;
  info.limits.sub_pixel_precision_bits = p.limits.subPixelPrecisionBits;
  info.limits.viewport_sub_pixel_bits = p.limits.viewportSubPixelBits;
  info.limits.strict_lines = p.limits.strictLines == VK_TRUE;
  info.limits.standard_sample_locations = p.limits.standardSampleLocations == VK_TRUE;
  info.limits.line_width_min = p.limits.lineWidthRange[0];
  info.limits.line_width_max = p.limits.lineWidthRange[1];
  info.depth_formats = renderable_depth_formats(device);
  info.sample_counts = sample_count_list(p.limits.framebufferColorSampleCounts & p.limits.framebufferDepthSampleCounts);
  info.is_lavapipe =
      (has_driver && driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE) || info.name.find("llvmpipe") != std::string::npos;
  // docs/lavapipe-rules.md §1.3, §7.1: whether lavapipe's JIT fuses llvm.fmuladd here.
  info.fma = info.is_lavapipe && lavapipe_fuses_on_this_host();
  return info;
}

std::string format_device_list(const std::vector<DeviceInfo>& devices) {
  std::string list;
  for (const DeviceInfo& d : devices) {
    if (!list.empty()) list += "; ";
    list += fmt::format("{}: {} [{}]", d.index, d.name, d.type);
  }
  return list.empty() ? std::string("none") : list;
}

uint32_t choose_device(const std::vector<DeviceInfo>& devices, const std::string& selector) {
  const bool is_index = !selector.empty() &&
                        std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); });
  if (is_index) {
    const unsigned long index = selector.size() <= 9 ? std::stoul(selector) : devices.size();
    if (index < devices.size()) return static_cast<uint32_t>(index);
    throw EnvironmentError(
        fmt::format("no Vulkan device with index {}; devices: {}", selector, format_device_list(devices)));
  }
  const std::string wanted = selector.empty() ? std::string("llvmpipe") : selector;
  for (const DeviceInfo& d : devices) {
    if (contains_ignoring_case(d.name, wanted)) return d.index;
  }
  const std::string hint =
      selector.empty() ? std::string("; for lavapipe, apt-get install mesa-vulkan-drivers") : std::string();
  throw EnvironmentError(fmt::format("no Vulkan device whose name contains \"{}\"; devices: {}{}", wanted,
                                     format_device_list(devices), hint));
}

}  // namespace rastercmp::vk
