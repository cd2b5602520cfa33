#include "vk_reference/vk_instance.hpp"

#include <cstring>

#include "model/errors.hpp"
#include "vk_reference/vk_check.hpp"
#include "vk_reference/vk_loader.hpp"
#include "vk_reference/vk_shader_cache.hpp"

namespace rastercmp::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool layer_present(const char* name) {
  uint32_t count = 0;
  check(api().vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
  std::vector<VkLayerProperties> layers(count);
  check(api().vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties");
  for (const VkLayerProperties& layer : layers) {
    if (std::strcmp(layer.layerName, name) == 0) return true;
  }
  return false;
}

const char* severity_name(VkDebugUtilsMessageSeverityFlagBitsEXT severity) {
  return (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
}

VKAPI_ATTR VkBool32 VKAPI_CALL collect_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                               VkDebugUtilsMessageTypeFlagsEXT,
                                               const VkDebugUtilsMessengerCallbackDataEXT* data, void* user_data) {
  auto* log = static_cast<MessageLog*>(user_data);
  std::string text = severity_name(severity);
  text += ": ";
  if (data->pMessageIdName != nullptr) text += std::string(data->pMessageIdName) + ": ";
  if (data->pMessage != nullptr) text += data->pMessage;
  const std::lock_guard<std::mutex> lock(log->mutex);
  log->messages.push_back(std::move(text));
  return VK_FALSE;  // never abort the call that triggered the message
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(MessageLog* log) {
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = collect_message;
  info.pUserData = log;
  return info;
}

uint32_t instance_api_version() {
  uint32_t version = VK_API_VERSION_1_0;
  if (api().vkEnumerateInstanceVersion == nullptr) return VK_API_VERSION_1_1;  // a Vulkan 1.0 loader
  check(api().vkEnumerateInstanceVersion(&version), "vkEnumerateInstanceVersion");
  // Vulkan 1.2 for VkPhysicalDeviceDriverProperties; a 1.1 loader still serves 1.1 devices.
  return version >= VK_API_VERSION_1_2 ? VK_API_VERSION_1_2 : VK_API_VERSION_1_1;
}

}  // namespace

Instance::Instance(bool validate) {
  key_shader_cache_by_vector_width();  // before the driver creates its screen and opens the cache
  if (validate && !layer_present(kValidationLayer)) {
    throw EnvironmentError(std::string(kValidationLayer) +
                           " is not installed: apt-get install vulkan-validationlayers");
  }
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "rastercmp";
  app.apiVersion = instance_api_version();

  const char* layers[] = {kValidationLayer};
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  VkDebugUtilsMessengerCreateInfoEXT debug_info = messenger_info(log_.get());
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pApplicationInfo = &app;
  if (validate) {
    info.pNext = &debug_info;  // also reports problems inside vkCreateInstance itself
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = layers;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = extensions;
  }
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult created = api().vkCreateInstance(&info, nullptr, &instance);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER) {
    throw EnvironmentError(std::string("no Vulkan driver found (vkCreateInstance: ") + result_name(created) + "); " +
                           kInstallVulkanHint);
  }
  check(created, "vkCreateInstance");
  instance_ = Owned<VkInstance>(instance, [](VkInstance h) { api().vkDestroyInstance(h, nullptr); });

  if (validate) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        api().vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        api().vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (create == nullptr || destroy == nullptr) {
      throw EnvironmentError("VK_EXT_debug_utils is unavailable: apt-get install vulkan-validationlayers");
    }
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    check(create(instance, &debug_info, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
    messenger_ = Owned<VkDebugUtilsMessengerEXT>(
        messenger, [instance, destroy](VkDebugUtilsMessengerEXT h) { destroy(instance, h, nullptr); });
  }
}

std::vector<VkPhysicalDevice> Instance::physical_devices() const {
  uint32_t count = 0;
  check(api().vkEnumeratePhysicalDevices(get(), &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  check(api().vkEnumeratePhysicalDevices(get(), &count, devices.data()), "vkEnumeratePhysicalDevices");
  devices.resize(count);
  if (devices.empty()) {
    throw EnvironmentError(std::string("no Vulkan device found; ") + kInstallVulkanHint);
  }
  return devices;
}

}  // namespace rastercmp::vk
