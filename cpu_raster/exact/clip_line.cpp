#include "cpu_raster/exact/clip_line.hpp"

#include <bit>
#include <cmath>

#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/float_ops.hpp"

namespace rastercmp::cpu {
namespace {

float max2(float a, float b) { return a > b ? a : b; }  // Mesa MAX2

// do_clip_line's passes over the planes of `mask`: false when the line is discarded (a non-finite
// distance: `discarded` set) or clipped away (t0 + t1 >= 1).
bool accumulate_t(const ClipVertex& v0, const ClipVertex& v1, uint32_t mask, float& t0, float& t1, bool& discarded) {
  for (; mask != 0; mask &= mask - 1) {
    const uint32_t plane = uint32_t(std::countr_zero(mask));
    const float dp0 = plane_distance(v0.pos_clip, plane);
    const float dp1 = plane_distance(v1.pos_clip, plane);
    if (is_inf_or_nan(dp0) || is_inf_or_nan(dp1)) {
      discarded = true;
      return false;
    }
    if (dp1 < 0.0f) t1 = max2(t1, dp1 / (dp1 - dp0));
    if (dp0 < 0.0f) t0 = max2(t0, dp0 / (dp0 - dp1));
    if (t0 + t1 >= 1.0f) return false;
  }
  return true;
}

}  // namespace

ClippedLine clip_line(const std::array<ClipVertex, 2>& line, const ViewportTransform& viewport, uint32_t inside_planes,
                      LineXyClip xy) {
  ClippedLine result;
  result.line = line;
  const ClipVertex& v0 = line[0];
  const ClipVertex& v1 = line[1];
  const uint32_t union_mask = v0.clip_mask | v1.clip_mask;
  bool discarded = false;
  if (union_mask == 0) {  // passed unchanged (§1.5)
    // WorkSkips::clip_only_when_needed off: the passes run anyway. Every distance is >= 0, so t0 and
    // t1 stay 0, and only endpoints with a mask bit would be replaced: the line is unchanged.
    if (inside_planes != 0) accumulate_t(v0, v1, inside_planes, result.t0, result.t1, discarded);
    return result;
  }
  uint32_t clip_planes = union_mask;
  if (xy == LineXyClip::GuardBand) {  // draw_pipe_clip.c clip_line_guard_xy (§8.2)
    constexpr uint32_t kXyPlanes = (1u << kClipRight) | (1u << kClipLeft) | (1u << kClipBottom) | (1u << kClipTop);
    clip_planes = union_mask & ~kXyPlanes;
    // Outside in x or y only, even both endpoints beyond the same edge (a wide line reaches in):
    // drawn whole, with the JIT window coordinates.
    if (clip_planes == 0) {
      const bool behind = v0.pos_clip.w <= 0.0f && v1.pos_clip.w <= 0.0f;
      const bool nan = std::isnan(v0.pos_clip.x) || std::isnan(v0.pos_clip.y) || std::isnan(v1.pos_clip.x) ||
                       std::isnan(v1.pos_clip.y);
      result.fate = behind || nan ? ClipFate::Outside : ClipFate::Inside;
      return result;
    }
  }
  if ((v0.clip_mask & v1.clip_mask) != 0) {  // any shared bit, x and y included
    result.fate = ClipFate::Outside;
    return result;
  }
  float& t0 = result.t0;
  float& t1 = result.t1;
  // An endpoint outside any plane is replaced below, even when only x or y put it there (t = 0).
  if (!accumulate_t(v0, v1, clip_planes, t0, t1, discarded)) {
    result.fate = discarded ? ClipFate::Discarded : ClipFate::Outside;  // Outside: clipped away entirely
    return result;
  }
  result.fate = ClipFate::Clipped;
  if (v0.clip_mask != 0) result.line[0] = interpolate_clip_vertex(t0, v0, v1, viewport);
  if (v1.clip_mask != 0) result.line[1] = interpolate_clip_vertex(t1, v1, v0, viewport);
  return result;
}

}  // namespace rastercmp::cpu
