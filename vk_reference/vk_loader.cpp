#include "vk_reference/vk_loader.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <string>

#include "model/errors.hpp"

namespace rastercmp::vk {
namespace {

Api resolve(void* library, const std::string& file) {
  Api api;
  api.vkGetInstanceProcAddr = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(library, "vkGetInstanceProcAddr"));
  if (api.vkGetInstanceProcAddr == nullptr) {
    throw EnvironmentError(file + " is not a Vulkan loader (no vkGetInstanceProcAddr); " + kInstallVulkanHint);
  }
  const auto missing = [&file](const char* name) {
    return EnvironmentError(file + " lacks " + name + " (a Vulkan 1.1 loader is needed); " + kInstallVulkanHint);
  };
#define RASTERCMP_VK_GLOBAL(name) \
  api.name = reinterpret_cast<PFN_##name>(api.vkGetInstanceProcAddr(VK_NULL_HANDLE, #name));
  RASTERCMP_VK_GLOBAL_COMMANDS(RASTERCMP_VK_GLOBAL)
#undef RASTERCMP_VK_GLOBAL
  if (api.vkCreateInstance == nullptr) throw missing("vkCreateInstance");
  if (api.vkEnumerateInstanceLayerProperties == nullptr) throw missing("vkEnumerateInstanceLayerProperties");
#define RASTERCMP_VK_CORE(name)                                   \
  api.name = reinterpret_cast<PFN_##name>(dlsym(library, #name)); \
  if (api.name == nullptr) throw missing(#name);
  RASTERCMP_VK_CORE_COMMANDS(RASTERCMP_VK_CORE)
#undef RASTERCMP_VK_CORE
  return api;
}

Api load() {
  const char* env = std::getenv(kLoaderEnv);
  const std::string file = (env != nullptr && *env != '\0') ? env : "libvulkan.so.1";
  // RTLD_LOCAL: the loader's symbols serve this table only, never a later library's lookups.
  void* library = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    const char* why = dlerror();
    throw EnvironmentError("cannot load the Vulkan loader " + file + " (" + (why != nullptr ? why : "dlopen failed") +
                           "); " + kInstallVulkanHint);
  }
  try {
    return resolve(library, file);  // the library then stays open for the life of the process
  } catch (...) {
    dlclose(library);
    throw;
  }
}

}  // namespace

const Api& api() {
  static const Api table = load();
  return table;
}

}  // namespace rastercmp::vk
