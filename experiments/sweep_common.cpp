#include "experiments/sweep_common.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/core.h>

#include "model/depth_format.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/image_io.hpp"

namespace rastercmp::experiments {

std::string num(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{}", value);
}

std::string flag(bool value) { return value ? "true" : "false"; }

const LavapipeRelease& installed_lavapipe_release() {
  static const LavapipeRelease* const release = [] {
    try {
      for (const DeviceInfo& device : list_vulkan_devices())
        if (device.is_lavapipe) return lavapipe_release_for_driver(device.driver_info).release;
    } catch (const EnvironmentError&) {
    }
    return &lavapipe_releases().front();
  }();
  return *release;
}

namespace {
const LavapipeRelease* g_reference_release = nullptr;  // set_reference_release; null: the installed one
}  // namespace

void set_reference_release(const LavapipeRelease& release) { g_reference_release = &release; }

CpuOptions exact_cpu_options() {
  CpuOptions options;
  options.fma = lavapipe_fuses_on_this_host();
  options.lavapipe = g_reference_release != nullptr ? g_reference_release : &installed_lavapipe_release();
  return options;
}

BackendPair render_both(VulkanRenderer& vk, const Scene& scene) {
  BackendPair pair;
  pair.cpu = render_cpu(scene, exact_cpu_options());
  pair.vk = vk.render(scene);
  return pair;
}

std::vector<DepthFormat> sweep_depth_formats() { return {kDepthFormats.begin(), kDepthFormats.end()}; }

void prepare_out_dir(const std::string& dir) { ensure_output_dir(dir); }

void write_json_file(const std::string& dir, const std::string& name, const std::string& json_text) {
  write_text_file_atomic((std::filesystem::path(dir) / name).string(), json_text);
}

}  // namespace rastercmp::experiments
