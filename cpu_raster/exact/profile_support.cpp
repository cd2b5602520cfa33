#include "cpu_raster/exact/profile_support.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "model/errors.hpp"

namespace rastercmp::cpu {
namespace {

std::string draw_path(size_t d) { return "$.draws[" + std::to_string(d) + "]"; }

void check_frame(const Scene& scene) {
  if (scene.width < 1 || scene.width > kMaxFramebufferSide || scene.height < 1 || scene.height > kMaxFramebufferSide)
    throw InputError(scene.source_path, "$.width", "expected a framebuffer of 1..16384 pixels per side");
  if (scene.samples != 1 && scene.samples != 4)
    throw InputError(scene.source_path, "$.samples", "expected 1 or 4 samples (lavapipe's sample counts)");
  if (scene.draws.size() > kMaxDraws) throw InputError(scene.source_path, "$.draws", "expected at most 255 draws");
  const Viewport v = scene.effective_viewport();
  const bool finite = std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.width) && std::isfinite(v.height);
  const auto in_bounds = [](double value) { return value >= -32768.0 && value <= 32768.0; };
  if (!finite || !in_bounds(v.x) || !in_bounds(v.y) || !in_bounds(double(v.x) + v.width) ||
      !in_bounds(double(v.y) + v.height) || !(v.width > 0) || std::fabs(v.height) > 16384 || v.width > 16384)
    throw InputError(scene.source_path, "$.viewport", "expected a viewport inside viewportBoundsRange ±32768");
}

void check_indices(const Scene& scene, size_t d) {
  const Draw& draw = scene.draws[d];
  if (indices_in_range(draw)) return;
  for (size_t k = 0; k < draw.indices.size(); ++k)  // name the first index out of range
    if (draw.indices[k] >= draw.positions_clip.size())
      throw InputError(scene.source_path, draw_path(d) + ".indices[" + std::to_string(k) + "]",
                       "expected an index below the number of positions");
}

void check_draw_state(const Scene& scene, size_t d) {
  const Draw& draw = scene.draws[d];
  if (draw.topology == Topology::PointList)
    throw NotSupportedError(draw_path(d) +
                            ": point_list is not reproduced by the CPU lavapipe profile "
                            "(lavapipe draws points through its guard-band point path, which is not modelled)");
  if (is_triangle_topology(draw.topology) && draw.state.polygon_mode != PolygonMode::Fill)
    throw NotSupportedError(draw_path(d) + ": polygon_mode \"" + to_string(draw.state.polygon_mode) +
                            "\" is not reproduced by the CPU lavapipe profile (lavapipe converts such polygons to "
                            "lines or points in its draw module, with the bias applied per vertex)");
  if (is_line_topology(draw.topology) && draw.state.line_mode == LineMode::RectangularSmooth)
    throw NotSupportedError(draw_path(d) +
                            ": line_mode \"rectangular_smooth\" is not reproduced by the CPU lavapipe "
                            "profile (lavapipe draws smooth lines with its anti-aliased line stage, a shader effect)");
}

// The largest index (0 for none) in a loop without an exit, which the compiler vectorises (the
// index scan runs on every render: 12 MiB for a million indexed triangles). Also compiled for
// AVX2, picked at load time: the baseline's SSE2 has no unsigned maximum (vpmaxud), and its
// emulation made the scan take 8% of a one-thread fast render of grid_180k.
__attribute__((target_clones("avx2", "default"))) uint32_t largest_index(const uint32_t* indices, size_t count) {
  uint32_t largest = 0;
  for (size_t i = 0; i < count; ++i) largest = std::max(largest, indices[i]);
  return largest;
}

}  // namespace

bool indices_in_range(const Draw& draw) {
  return draw.indices.empty() || largest_index(draw.indices.data(), draw.indices.size()) < draw.positions_clip.size();
}

void check_lavapipe_profile_support(const Scene& scene) {
  check_frame(scene);
  for (size_t d = 0; d < scene.draws.size(); ++d) {
    check_indices(scene, d);
    check_draw_state(scene, d);
  }
}

void check_lavapipe_profile_support_but_indices(const Scene& scene) {
  try {
    check_frame(scene);
    for (size_t d = 0; d < scene.draws.size(); ++d) check_draw_state(scene, d);
  } catch (...) {
    check_lavapipe_profile_support(scene);  // an index of an earlier draw may come first
    throw;
  }
}

}  // namespace rastercmp::cpu
