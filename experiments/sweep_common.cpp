#include "experiments/sweep_common.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/core.h>

#include "model/depth_format.hpp"
#include "model/host.hpp"
#include "model/image_io.hpp"

namespace rastercmp::experiments {

std::string num(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{}", value);
}

std::string flag(bool value) { return value ? "true" : "false"; }

CpuOptions exact_cpu_options() {
  CpuOptions options;
  options.fma = lavapipe_fuses_on_this_host();
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
