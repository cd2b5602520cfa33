#include "vk_reference/vk_shader_cache.hpp"

#include <cstdlib>
#include <filesystem>
#include <mutex>

namespace rastercmp::vk {
namespace {

std::optional<std::string> variable(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr) return std::nullopt;
  return std::string(value);
}

bool ends_with_folder(const std::string& path, const std::string& folder) {
  std::string trimmed = path;
  while (trimmed.size() > 1 && trimmed.back() == '/') trimmed.pop_back();
  if (trimmed.size() < folder.size()) return false;
  if (trimmed.compare(trimmed.size() - folder.size(), folder.size(), folder) != 0) return false;
  return trimmed.size() == folder.size() || trimmed[trimmed.size() - folder.size() - 1] == '/';
}

bool set(const std::optional<std::string>& value) { return value.has_value() && !value->empty(); }

}  // namespace

std::string shader_cache_folder_name(const std::string& vector_width) {
  std::string name = "rastercmp-lp-native-vector-width-";
  for (const char c : vector_width) {
    const bool plain = (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
    name += plain ? c : '_';
  }
  return name;
}

ShaderCacheSetting shader_cache_setting(const ShaderCacheEnvironment& environment) {
  ShaderCacheSetting setting;
  // Mesa reads an empty LP_NATIVE_VECTOR_WIDTH as unset (debug_get_num_option): the default width.
  if (!set(environment.lp_native_vector_width)) return setting;
  // MESA_SHADER_CACHE_DISABLE set to anything: the user decided; an off cache cannot mix widths.
  if (environment.mesa_shader_cache_disable.has_value()) return setting;
  const std::string folder = shader_cache_folder_name(*environment.lp_native_vector_width);
  std::string root;
  if (set(environment.mesa_shader_cache_dir)) {
    if (ends_with_folder(*environment.mesa_shader_cache_dir, folder)) return setting;
    root = *environment.mesa_shader_cache_dir;
  } else if (set(environment.xdg_cache_home)) {
    root = *environment.xdg_cache_home;
  } else if (set(environment.home)) {
    root = *environment.home + "/.cache";
  } else {
    setting.action = ShaderCacheSetting::Action::Disable;
    return setting;
  }
  while (root.size() > 1 && root.back() == '/') root.pop_back();
  setting.action = ShaderCacheSetting::Action::UseDir;
  setting.dir = (root == "/" ? root : root + "/") + folder;
  return setting;
}

void key_shader_cache_by_vector_width() {
  static std::once_flag once;
  std::call_once(once, [] {
    const ShaderCacheSetting setting = shader_cache_setting({variable("LP_NATIVE_VECTOR_WIDTH"),
                                                             variable("MESA_SHADER_CACHE_DIR"),
                                                             variable("MESA_SHADER_CACHE_DISABLE"),
                                                             variable("XDG_CACHE_HOME"), variable("HOME")});
    switch (setting.action) {
      case ShaderCacheSetting::Action::Keep:
        break;
      case ShaderCacheSetting::Action::UseDir: {
        // Mesa creates only the last folder of MESA_SHADER_CACHE_DIR; one it cannot create turns
        // the cache off, and so does this.
        std::error_code error;
        std::filesystem::create_directories(setting.dir, error);
        if (error) {
          setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
        } else {
          setenv("MESA_SHADER_CACHE_DIR", setting.dir.c_str(), 1);
        }
        break;
      }
      case ShaderCacheSetting::Action::Disable:
        setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
        break;
    }
  });
}

}  // namespace rastercmp::vk
