#include "cpu_raster/clip_line.hpp"

#include <bit>

#include "cpu_raster/clip_test.hpp"
#include "cpu_raster/float_ops.hpp"

namespace rastercmp::cpu {
namespace {

float max2(float a, float b) { return a > b ? a : b; }  // Mesa MAX2

}  // namespace

ClippedLine clip_line(const std::array<ClipVertex, 2>& line, const ViewportTransform& viewport) {
  ClippedLine result;
  result.line = line;
  const ClipVertex& v0 = line[0];
  const ClipVertex& v1 = line[1];
  const uint32_t union_mask = v0.clip_mask | v1.clip_mask;
  if (union_mask == 0) return result;
  if ((v0.clip_mask & v1.clip_mask) != 0) {
    result.fate = ClipFate::Outside;
    return result;
  }
  float t0 = 0.0f, t1 = 0.0f;
  for (uint32_t mask = union_mask; mask != 0; mask &= mask - 1) {
    const uint32_t plane = uint32_t(std::countr_zero(mask));
    const float dp0 = plane_distance(v0.pos_clip, plane);
    const float dp1 = plane_distance(v1.pos_clip, plane);
    if (is_inf_or_nan(dp0) || is_inf_or_nan(dp1)) {
      result.fate = ClipFate::Discarded;
      return result;
    }
    if (dp1 < 0.0f) t1 = max2(t1, dp1 / (dp1 - dp0));
    if (dp0 < 0.0f) t0 = max2(t0, dp0 / (dp0 - dp1));
    if (t0 + t1 >= 1.0f) {
      result.fate = ClipFate::Outside;  // clipped away entirely
      return result;
    }
  }
  result.fate = ClipFate::Clipped;
  if (v0.clip_mask != 0) result.line[0] = interpolate_clip_vertex(t0, v0, v1, viewport);
  if (v1.clip_mask != 0) result.line[1] = interpolate_clip_vertex(t1, v1, v0, viewport);
  return result;
}

}  // namespace rastercmp::cpu
