#include "cpu_raster/fast/lean_setup.hpp"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "cpu_raster/exact/binned_triangle.hpp"
#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/line_setup.hpp"
#include "cpu_raster/exact/triangle_setup.hpp"
#include "cpu_raster/fast/cpu_features.hpp"

namespace rastercmp::cpu::fast {
namespace {

// snap_vertex with nearest-even rounding: fl(fl(x - offset) * 256) rounded to an integral float
// (roundss to nearest, no exception: nearbyint in the default rounding mode, the exact path's
// round_nearest_even), then bounded_int32's test.
RASTERCMP_AVX2 inline bool snap_nearest_even(float window, float pixel_offset, int32_t& raw) {
  const __m128 scaled = _mm_set_ss((window - pixel_offset) * float(kFixedOne));
  const float rounded = _mm_cvtss_f32(_mm_round_ss(scaled, scaled, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
  if (!(std::fabs(rounded) <= float(Fixed24_8::kMaxMagnitude))) return false;  // NaN too
  raw = static_cast<int32_t>(rounded);
  return true;
}

// subpixel_snap(a) of a line (line_snap, line_snap_lrintf): fl(256 * a) rounded by the release's
// util_iround, then the set-up bound. 22.3.6: trunc(f + 0.5f) for f >= 0, trunc(f - 0.5f)
// otherwise, each a rounded float add; from 23.1 lrintf, to nearest even (§8.1), whose int32
// wrapping the bound leaves out. false where the full set-up decides (NaN, beyond the bound).
// The 22.3.6 add without a branch on the sign: f + copysign(0.5f, f) is f - 0.5f for f < 0 (the
// same rounded operation), f + 0.5f for f >= +0; for f = -0 it gives -0.5f where util_iround adds
// 0.5f, both truncated to 0. The MXCSR flags the watch reads (DE, UE) are those of the same add.
RASTERCMP_AVX2 inline bool snap_line(float pixels, bool lrintf, int64_t& raw) {
  const float scaled = float(kFixedOne) * pixels;
  __m128 v = _mm_set_ss(lrintf ? scaled : scaled + std::copysign(0.5f, scaled));
  v = lrintf ? _mm_round_ss(v, v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)
             : _mm_round_ss(v, v, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
  const float rounded = _mm_cvtss_f32(v);
  if (!(std::fabs(rounded) <= float(Fixed24_8::kMaxMagnitude))) return false;  // NaN too
  raw = int64_t(rounded);
  return true;
}

// The common tail of both set-ups: the region, its scissor planes and visit, then the depth plane
// (set by `depth_plane` where set-up forms one).
template <class DepthPlaneOf>
RASTERCMP_AVX2 inline LeanSetup place_lean(RasterPrimitive& out, const PixelRect& bbox, bool per_sample,
                                           const SetupContext& ctx, DepthPlaneOf&& depth_plane) {
  if (!place_in_region(out, bbox, ctx.region, ctx.framebuffer, per_sample, false,
                       ctx.rules.has(LavapipeRule::NoMsaaRegionLeak)))
    return LeanSetup::Dropped;
  out.has_depth = false;
  out.depth = DepthPlane{};
  out.offset = DepthOffset{};
  if (ctx.depth_plane_wanted()) {  // without an active test only when the depth skip is off
    out.has_depth = ctx.depth_active();
    depth_plane(out);
  }
  return LeanSetup::Drawn;
}

}  // namespace

RASTERCMP_AVX2 LeanSetup setup_triangle_lean(const std::array<WindowVertex, 3>& window_in, uint32_t owner,
                                             const SetupContext& ctx, RasterPrimitive& out) {
  if (ctx.methods.snap != SnapRounding::NearestEven) return LeanSetup::Full;
  const float pixel_offset = ctx.multisample ? 0.0f : 0.5f;  // calc_fixed_position
  std::array<FixedPoint, 3> fixed;
  for (size_t i = 0; i < 3; ++i) {
    int32_t x = 0, y = 0;
    if (!snap_nearest_even(window_in[i].x, pixel_offset, x) || !snap_nearest_even(window_in[i].y, pixel_offset, y))
      return LeanSetup::Full;
    fixed[i] = FixedPoint{Fixed24_8{x}, Fixed24_8{y}};
  }
  if (!in_direct_range(fixed)) return LeanSetup::Full;
  const int64_t area = doubled_area(fixed);
  if (area == 0) return LeanSetup::Dropped;  // always dropped, whatever the cull mode (§2.3)
  const RasterState& state = *ctx.state;
  if (face_culled((area > 0) == (state.front_face == FrontFace::CounterClockwise), state.cull_mode))
    return LeanSetup::Dropped;
  std::array<WindowVertex, 3> window = window_in;
  if (area < 0) {  // rotate_fixed_position_12 with flatshade_first: (v0, v2, v1)
    std::swap(fixed[1], fixed[2]);
    std::swap(window[1], window[2]);
  }
  out.owner = owner;
  out.is_line = false;
  out.per_sample = ctx.multisample;
  out.edge_count = 3;
  out.binned = nullptr;
  out.planes.count = 0;
  for (size_t i = 0; i < 3; ++i) {
    out.vertex_fixed[i] = fixed[i];
    out.planes.push(make_edge(fixed[i], fixed[(i + 1) % 3], ctx.methods.tie_break));
  }
  out.vertex_fixed[3] = FixedPoint{};
  return place_lean(out, triangle_bbox(fixed), ctx.multisample, ctx, [&](RasterPrimitive& p) {
    p.depth = triangle_depth_plane(window, pixel_offset);
    p.offset = triangle_depth_offset(window, state.depth_bias, ctx.depth_format, ctx.skips.bias_only_when_enabled,
                                     unorm_bias_units(ctx.rules));
  });
}

// setup_line (line_setup.cpp) for a rectangular line: v1 - t, v2 - t, v2 + t, v1 + t with t the
// snapped half-width normal, the endpoints snapped at the pixel offset, the box
// ((min + 255) >> 8, ((max + 255) >> 8) - 1), four edges, the region, linear_coef's depth plane.
// The corners' int32 sums of 23.1 and later do not wrap: every snap is within 2^25.
RASTERCMP_AVX2 LeanSetup setup_line_lean(const std::array<WindowVertex, 2>& window, uint32_t owner,
                                         const SetupContext& ctx, RasterPrimitive& out) {
  const RasterState& state = *ctx.state;
  if (state.line_mode == LineMode::Bresenham) return LeanSetup::Full;
  const WindowVertex &v1 = window[0], &v2 = window[1];
  const float dx = v1.x - v2.x, dy = v1.y - v2.y;
  const float area = dx * dx + dy * dy;
  if (area == 0) return LeanSetup::Dropped;  // Degenerate
  const float one_over_area = 1.0f / area;  // where setup_line forms it: the same operations, flags too
  const bool per_sample = line_rasterizes_per_sample(ctx);
  const float pixel_offset = per_sample ? 0.0f : 0.5f;  // setup->multisample ? 0 : pixel_offset
  const bool lrintf = ctx.rules.has(LavapipeRule::LineRoundHalfToEven);
  const float scale = (state.line_width * 0.5f) / std::sqrt(area);
  int64_t tx = 0, ty = 0, x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  if (!snap_line(-dy * scale, lrintf, tx) || !snap_line(dx * scale, lrintf, ty) ||
      !snap_line(v1.x - pixel_offset, lrintf, x1) || !snap_line(v2.x - pixel_offset, lrintf, x2) ||
      !snap_line(v1.y - pixel_offset, lrintf, y1) || !snap_line(v2.y - pixel_offset, lrintf, y2))
    return LeanSetup::Full;
  const int64_t qx[4] = {x1 - tx, x2 - tx, x2 + tx, x1 + tx}, qy[4] = {y1 - ty, y2 - ty, y2 + ty, y1 + ty};
  std::array<FixedPoint, 4> corners;
  int64_t min_x = qx[0], max_x = qx[0], min_y = qy[0], max_y = qy[0];
  for (size_t i = 0; i < 4; ++i) {
    if (qx[i] > Fixed24_8::kMaxMagnitude || qx[i] < -Fixed24_8::kMaxMagnitude || qy[i] > Fixed24_8::kMaxMagnitude ||
        qy[i] < -Fixed24_8::kMaxMagnitude)
      return LeanSetup::Full;  // quad_corners' bound
    corners[i] = FixedPoint{Fixed24_8{int32_t(qx[i])}, Fixed24_8{int32_t(qy[i])}};
    min_x = std::min(min_x, qx[i]);
    max_x = std::max(max_x, qx[i]);
    min_y = std::min(min_y, qy[i]);
    max_y = std::max(max_y, qy[i]);
  }
  if (!quad_in_direct_range(corners)) return LeanSetup::Full;
  const PixelRect bbox{int32_t((min_x + kFixedOne - 1) >> kFixedOrder), int32_t((min_y + kFixedOne - 1) >> kFixedOrder),
                       int32_t(((max_x + kFixedOne - 1) >> kFixedOrder) - 1),
                       int32_t(((max_y + kFixedOne - 1) >> kFixedOrder) - 1)};
  out.owner = owner;
  out.is_line = true;
  out.per_sample = per_sample;
  out.edge_count = 4;
  out.binned = nullptr;
  out.planes.count = 0;
  out.vertex_fixed = corners;
  for (size_t i = 0; i < 4; ++i) out.planes.push(make_edge(corners[i], corners[(i + 1) % 4], ctx.methods.tie_break));
  return place_lean(out, bbox, per_sample, ctx, [&](RasterPrimitive& p) {
    // setup->pixel_offset: 0.5, or from 25.3 0 when the line is multisampled (§8.5)
    const bool offset_zero = per_sample && ctx.rules.has(LavapipeRule::MsaaLineDepthAtCentre);
    p.depth = line_depth_plane(v1, v2, dx, dy, one_over_area, offset_zero ? 0.0f : 0.5f);
  });
}

}  // namespace rastercmp::cpu::fast
