#include "cpu_raster/exact/triangle_setup.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

namespace rastercmp::cpu {
namespace {

// calc_fixed_position as llvmpipe runs it past the bound: cvtps2dq saturating (rules §7.5).
// nullopt for NaN, which this project drops (rules §7.6).
std::optional<std::array<FixedPoint, 3>> snap_triangle_saturating(const std::array<WindowVertex, 3>& window,
                                                                  float pixel_offset, SnapRounding rounding) {
  std::array<FixedPoint, 3> fixed;
  for (size_t i = 0; i < 3; ++i) {
    if (std::isnan(window[i].x) || std::isnan(window[i].y)) return std::nullopt;
    fixed[i] = FixedPoint{Fixed24_8{snap_vertex_saturating(window[i].x, pixel_offset, rounding)},
                          Fixed24_8{snap_vertex_saturating(window[i].y, pixel_offset, rounding)}};
  }
  return fixed;
}

// The binned coverage of a placed triangle: its edges and the scissor planes place_in_region added.
std::shared_ptr<const BinnedTriangle> bin_placed(const RasterPrimitive& raster, const PixelRect& region,
                                                 const PixelRect& framebuffer, bool multisample) {
  const std::array<FixedPoint, 3> v{raster.vertex_fixed[0], raster.vertex_fixed[1], raster.vertex_fixed[2]};
  std::array<LpPlane, 8> planes{};
  const std::array<LpPlane, 3> edges = lp_edge_planes(v);
  std::copy(edges.begin(), edges.end(), planes.begin());
  for (uint32_t i = 3; i < raster.planes.count; ++i) planes[i] = lp_scissor_plane(raster.planes.plane[i]);
  return std::make_shared<const BinnedTriangle>(
      bin_triangle(planes, raster.planes.count, raster.bbox, region, framebuffer, multisample));
}

}  // namespace

std::optional<std::array<FixedPoint, 3>> snap_triangle(const std::array<WindowVertex, 3>& window, float pixel_offset,
                                                       SnapRounding rounding) {
  std::array<FixedPoint, 3> fixed;
  for (size_t i = 0; i < 3; ++i) {
    const auto x = snap_vertex(window[i].x, pixel_offset, rounding);
    const auto y = snap_vertex(window[i].y, pixel_offset, rounding);
    if (!x || !y) return std::nullopt;
    fixed[i] = FixedPoint{*x, *y};
  }
  return fixed;
}

// area = dx01*dy20 - dx20*dy01 (§2.3): > 0 is llvmpipe's "ccw".
int64_t doubled_area(const std::array<FixedPoint, 3>& v) {
  const int64_t dx01 = v[0].x.wide() - v[1].x.wide(), dy01 = v[0].y.wide() - v[1].y.wide();
  const int64_t dx20 = v[2].x.wide() - v[0].x.wide(), dy20 = v[2].y.wide() - v[0].y.wide();
  return dx01 * dy20 - dx20 * dy01;
}

// do_triangle_ccw: x0 = min >> 8, x1 = (max - 1) >> 8 (bottom_edge_rule = 0).
bool face_culled(bool front_facing, CullMode cull) {
  switch (cull) {
    case CullMode::None: return false;
    case CullMode::Front: return front_facing;
    case CullMode::Back: return !front_facing;
    case CullMode::FrontAndBack: return true;
  }
  return false;
}

TriangleSetup setup_triangle(const std::array<WindowVertex, 3>& window_in, uint32_t owner, const SetupContext& ctx) {
  TriangleSetup setup;
  const RasterState& state = *ctx.state;
  const float pixel_offset = ctx.multisample ? 0.0f : 0.5f;  // calc_fixed_position
  // Past the 24.8 bound, or with edges too long for llvmpipe's int32 set-up, the triangle follows
  // llvmpipe's own wrapping arithmetic (binned_triangle.hpp, docs/lavapipe-rules.md §7.5).
  auto snapped = snap_triangle(window_in, pixel_offset, ctx.methods.snap);
  const bool binned = !snapped || !in_direct_range(*snapped);
  if (!snapped) snapped = snap_triangle_saturating(window_in, pixel_offset, ctx.methods.snap);
  if (!snapped) {
    setup.fate = SetupFate::NonFinite;
    return setup;
  }
  std::array<FixedPoint, 3> fixed = *snapped;
  std::array<WindowVertex, 3> window = window_in;
  setup.bbox = binned ? wrapped_triangle_bbox(fixed) : triangle_bbox(fixed);
  setup.area = binned ? wrapped_doubled_area(fixed) : doubled_area(fixed);
  if (setup.area == 0) {  // always dropped, whatever the cull mode (§2.3)
    setup.fate = SetupFate::Degenerate;
    return setup;
  }
  setup.front_facing = (setup.area > 0) == (state.front_face == FrontFace::CounterClockwise);
  if (face_culled(setup.front_facing, state.cull_mode)) {
    setup.fate = SetupFate::Culled;
    return setup;
  }
  if (setup.area < 0) {  // rotate_fixed_position_12 with flatshade_first: (v0, v2, v1)
    std::swap(fixed[1], fixed[2]);
    std::swap(window[1], window[2]);
    setup.swapped = true;
  }
  RasterPrimitive& raster = setup.raster;
  raster.owner = owner;
  raster.per_sample = ctx.multisample;
  raster.edge_count = 3;
  for (size_t i = 0; i < 3; ++i) {
    raster.vertex_fixed[i] = fixed[i];
    raster.planes.push(binned ? EdgePlane{} : make_edge(fixed[i], fixed[(i + 1) % 3], ctx.methods.tie_break));
  }
  if (!place_in_region(raster, setup.bbox, ctx.region, ctx.framebuffer, ctx.multisample, binned,
                       ctx.rules.has(LavapipeRule::NoMsaaRegionLeak))) {
    setup.fate = SetupFate::OutsideRegion;
    return setup;
  }
  if (binned) {
    refuse_if_overflow_reworked(ctx.rules);
    raster.binned = bin_placed(raster, ctx.region, ctx.framebuffer, ctx.multisample);
  }
  if (ctx.depth_plane_wanted()) {  // without an active test only when the depth skip is off
    raster.has_depth = ctx.depth_active();
    raster.depth = triangle_depth_plane(window, pixel_offset);
    raster.offset = triangle_depth_offset(window, state.depth_bias, ctx.depth_format, ctx.skips.bias_only_when_enabled,
                                          unorm_bias_units(ctx.rules));
  }
  return setup;
}

}  // namespace rastercmp::cpu
