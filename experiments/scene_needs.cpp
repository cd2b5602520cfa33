#include "experiments/scene_needs.hpp"

#include <stdexcept>

#include "cpu_raster/exact/clip_test.hpp"

namespace rastercmp::experiments {
namespace {

bool any_vertex_outside(const Draw& draw) {
  const bool depth_clip = draw.state.depth_clip_enabled();
  const auto outside = [&](const glm::vec4& p) { return cpu::clip_mask(p, depth_clip) != 0; };
  if (draw.indices.empty()) {
    for (const glm::vec4& p : draw.positions_clip)
      if (outside(p)) return true;
    return false;
  }
  for (uint32_t i : draw.indices)
    if (i < draw.positions_clip.size() && outside(draw.positions_clip[i])) return true;
  return false;
}

}  // namespace

StageNeeds scene_needs(const Scene& scene) {
  StageNeeds needs;
  needs.msaa = scene.samples > 1;
  for (const Draw& draw : scene.draws) {
    needs.clipping = needs.clipping || any_vertex_outside(draw);
    needs.depth = needs.depth || (scene.depth_format != DepthFormat::None && draw.state.depth.test_enable);
    const DepthBias& bias = draw.state.depth_bias;
    needs.bias = needs.bias || (bias.enable && (bias.constant_factor != 0 || bias.slope_factor != 0));
    needs.lines = needs.lines || is_line_topology(draw.topology) || draw.state.polygon_mode == PolygonMode::Line;
    needs.culling = needs.culling || draw.state.cull_mode != CullMode::None;
  }
  return needs;
}

const std::vector<StageInfo>& pipeline_stages() {
  static const std::vector<StageInfo> stages{
      {"clipping", [](const StageNeeds& n) { return n.clipping; }, "clip"},
      {"depth", [](const StageNeeds& n) { return n.depth; }, "depth"},
      {"bias", [](const StageNeeds& n) { return n.bias; }, "bias"},
      {"msaa", [](const StageNeeds& n) { return n.msaa; }, std::nullopt},
      {"lines", [](const StageNeeds& n) { return n.lines; }, std::nullopt},
      {"culling", [](const StageNeeds& n) { return n.culling; }, std::nullopt},
  };
  return stages;
}

CpuOptions with_skip_off(CpuOptions options, const std::string& skip) {
  if (skip == "clip")
    options.skips.clip_only_when_needed = false;
  else if (skip == "depth")
    options.skips.depth_only_when_attached = false;
  else if (skip == "bias")
    options.skips.bias_only_when_enabled = false;
  else if (skip == "all")
    options.skips.clip_only_when_needed = options.skips.depth_only_when_attached =
        options.skips.bias_only_when_enabled = false;
  else
    throw std::invalid_argument("unknown work skip \"" + skip + "\"");
  return options;
}

}  // namespace rastercmp::experiments
