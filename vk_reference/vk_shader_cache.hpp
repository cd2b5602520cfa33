// Mesa's on-disk shader cache, kept apart per llvmpipe vector width.
//
// llvmpipe keys its disk cache without the vector width that LP_NATIVE_VECTOR_WIDTH sets: in Mesa
// 22.3.6 and 25.0.7, lp_disk_cache_create hashes two function identifiers, the GALLIVM_PERF flags
// (and in 25.0.7 the CPU caps, whose max_vector_bits the variable does not change), and
// draw_get_ir_cache_key hashes the variant key and the NIR. So a run with LP_NATIVE_VECTOR_WIDTH=128
// loads vertex shaders compiled at the default 256 bits: they store 8 vertices per step into an
// array that draw_pt_fetch_shade_pipeline_llvm.c sized for multiples of 4 (lp_native_vector_width
// / 32), and lavapipe's heap is corrupted (docs/lavapipe-rules.md, §7.8). A process that sets the
// width therefore gets a cache folder of its own for that width.
#pragma once

#include <optional>
#include <string>

namespace rastercmp::vk {

// The environment variables the decision reads (unset: nullopt).
struct ShaderCacheEnvironment {
  std::optional<std::string> lp_native_vector_width;  // LP_NATIVE_VECTOR_WIDTH
  std::optional<std::string> mesa_shader_cache_dir;   // MESA_SHADER_CACHE_DIR
  std::optional<std::string> mesa_shader_cache_disable;  // MESA_SHADER_CACHE_DISABLE
  std::optional<std::string> xdg_cache_home;          // XDG_CACHE_HOME
  std::optional<std::string> home;                    // HOME
};

struct ShaderCacheSetting {
  enum class Action {
    Keep,     // the default width, a cache the user turned off, or a folder already keyed
    UseDir,   // MESA_SHADER_CACHE_DIR=dir
    Disable,  // MESA_SHADER_CACHE_DISABLE=true: no folder to key (no HOME, no XDG_CACHE_HOME)
  };
  Action action = Action::Keep;
  std::string dir;
};

// The folder name a width gets: "rastercmp-lp-native-vector-width-" + the value, every character
// outside [0-9A-Za-z] written as '_', so the value cannot name another folder.
std::string shader_cache_folder_name(const std::string& vector_width);

// Pure: what the process must set. The folder is keyed under the cache root Mesa would use
// (MESA_SHADER_CACHE_DIR, else XDG_CACHE_HOME, else HOME/.cache); a MESA_SHADER_CACHE_DIR that
// already ends in the keyed folder (a child of a keyed parent) is kept.
ShaderCacheSetting shader_cache_setting(const ShaderCacheEnvironment& environment);

// Reads the environment and applies shader_cache_setting, once per process, before the first
// Vulkan instance exists (Mesa reads these variables when it creates its screen). The keyed
// folder is created here; where it cannot be, the cache is turned off.
void key_shader_cache_by_vector_width();

}  // namespace rastercmp::vk
