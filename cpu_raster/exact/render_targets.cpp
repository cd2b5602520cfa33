#include "cpu_raster/exact/render_targets.hpp"

#include "cpu_raster/exact/depth_sample.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu {

RenderTargets make_render_targets(const Scene& scene) {
  RenderTargets targets;
  targets.width = scene.width;
  targets.height = scene.height;
  targets.samples = scene.samples;
  targets.depth_format = scene.depth_format;
  const size_t count = size_t(scene.width) * scene.height * scene.samples;
  targets.owner.assign(count, kOwnerBackground);
  if (scene.has_depth()) targets.depth_raw.assign(count, clear_depth_raw(scene.depth_format, scene.depth_clear));
  return targets;
}

void move_into_result(RenderTargets&& targets, const std::string& device, bool fma, RenderResult& result) {
  result.backend = "cpu";
  result.device = device;
  result.fma = fma;
  result.width = targets.width;
  result.height = targets.height;
  result.samples = targets.samples;
  result.depth_format = targets.depth_format;
  result.owner = std::move(targets.owner);
  result.depth_raw = std::move(targets.depth_raw);
  result.coverage_class.clear();
}

}  // namespace rastercmp::cpu
