#include "cpu_raster/fast/lean_setup.hpp"

#include <immintrin.h>

#include <cmath>
#include <utility>

#include "cpu_raster/exact/binned_triangle.hpp"
#include "cpu_raster/exact/depth_plane.hpp"
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
  if (!place_in_region(out, triangle_bbox(fixed), ctx.region, ctx.framebuffer, ctx.multisample, false,
                       ctx.rules.has(LavapipeRule::NoMsaaRegionLeak)))
    return LeanSetup::Dropped;
  out.has_depth = false;
  out.depth = DepthPlane{};
  out.offset = DepthOffset{};
  if (ctx.depth_plane_wanted()) {  // without an active test only when the depth skip is off
    out.has_depth = ctx.depth_active();
    out.depth = triangle_depth_plane(window, pixel_offset);
    out.offset = triangle_depth_offset(window, state.depth_bias, ctx.depth_format, ctx.skips.bias_only_when_enabled,
                                       unorm_bias_units(ctx.rules));
  }
  return LeanSetup::Drawn;
}

}  // namespace rastercmp::cpu::fast
