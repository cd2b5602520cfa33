#include "cpu_raster/exact/line_setup.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "cpu_raster/exact/binned_triangle.hpp"

namespace rastercmp::cpu {
namespace {

// The half-pixel centre of the rasterizer state (half_pixel_center = true in lavapipe).
constexpr float kHalfPixelCenter = 0.5f;

struct Quad {
  std::array<int64_t, 4> x{}, y{};
};

struct Endpoint {
  float x, y;
};

// subpixel_snap and the int arithmetic of the quad's corners, as the release rounds (util_iround,
// §5.3, §8.1): 22.3.6 drops a line whose snap leaves Fixed24_8's bound (only non-finite or
// out-of-range input reaches it: lines are clipped in x and y); from 23.1 util_iround is lrintf,
// defined for every float, and the corners are int32 sums that wrap as Mesa's do.
struct LineSnap {
  bool lrintf = false;
  std::optional<int64_t> operator()(float value) const {
    if (lrintf) return int64_t(line_snap_lrintf(value));
    const std::optional<int32_t> fixed = line_snap(value);
    return fixed ? std::optional<int64_t>(*fixed) : std::nullopt;
  }
  std::optional<int32_t> round(float value) const {  // util_iround
    return lrintf ? std::optional<int32_t>(util_iround_lrintf(value)) : util_iround(value);
  }
  int64_t add(int64_t a, int64_t b) const { return lrintf ? int32_t(uint32_t(a) + uint32_t(b)) : a + b; }
  int64_t sub(int64_t a, int64_t b) const { return lrintf ? int32_t(uint32_t(a) - uint32_t(b)) : a - b; }
};

bool nonneg(float value) { return value >= 0; }  // lp_setup_line.c sign()
float fracf(float value) { return value - std::floor(value); }

// Rectangular quad: v1 - t, v2 - t, v2 + t, v1 + t with t the snapped half-width normal (§5.3).
std::optional<Quad> rectangular_quad(const LineSnap& snap, Endpoint v1, Endpoint v2, float dx, float dy, float area,
                                     float width, float pixel_offset) {
  const float scale = (width * 0.5f) / std::sqrt(area);
  const auto tx = snap(-dy * scale), ty = snap(dx * scale);
  const auto x1 = snap(v1.x - pixel_offset), x2 = snap(v2.x - pixel_offset);
  const auto y1 = snap(v1.y - pixel_offset), y2 = snap(v2.y - pixel_offset);
  if (!tx || !ty || !x1 || !x2 || !y1 || !y2) return std::nullopt;
  return Quad{{snap.sub(*x1, *tx), snap.sub(*x2, *tx), snap.add(*x2, *tx), snap.add(*x1, *tx)},
              {snap.sub(*y1, *ty), snap.sub(*y2, *ty), snap.add(*y2, *ty), snap.add(*y1, *ty)}};
}

// The diamond-exit decisions and end shifts of a Bresenham line, along its major axis "a" with
// minor axis "b" (x-major: a = x; y-major: a = y). Written once for both axes: the y-major code
// of lp_setup_line.c is the x-major one with the axes exchanged, except for the comparisons
// marked below, which differ between the two branches in Mesa and are reproduced as they are.
// Four "will draw" tests differ between releases when the start or end lies exactly on a pixel
// centre line (x1diff, x2diff, y1diff or y2diff == 0): the x-major rightward end, the y-major
// starts and the y-major downward end. 22.3.6 tests `>= 0` / `< 0` there (§5.4); from 23.2 each is
// a sign test per direction, `> 0` / `<= 0` (BresenhamEndSignTests, §8.3).
struct DiamondExit {
  bool draw_start = false, draw_end = false;
  float a_offset = 0, b_offset = 0, a_offset_end = 0, b_offset_end = 0;
  bool swap = false;  // the endpoints are exchanged before the quad is built
};

DiamondExit diamond_exit_x_major(Endpoint v1, Endpoint v2, float dx, float dy, bool sign_tests) {
  DiamondExit d;
  const float x1diff = v1.x - std::floor(v1.x) - 0.5f, y1diff = v1.y - std::floor(v1.y) - 0.5f;
  const float x2diff = v2.x - std::floor(v2.x) - 0.5f;
  float y2diff = v2.y - std::floor(v2.y) - 0.5f;
  const float dydx = dy / dx;
  if (y2diff == -0.5f && dy < 0.0f) y2diff = 0.5f;
  if (std::fabs(x1diff) + std::fabs(y1diff) < 0.5f)
    d.draw_start = true;
  else if (nonneg(x1diff) == nonneg(-dx))
    d.draw_start = false;
  else if (nonneg(-y1diff) != nonneg(dy))
    d.draw_start = true;
  else {
    const float yintersect = fracf(v1.y) + x1diff * dydx;
    d.draw_start = yintersect < 1.0f && yintersect > 0.0f;
  }
  if (std::fabs(x2diff) + std::fabs(y2diff) < 0.5f)
    d.draw_end = false;
  else if (nonneg(x2diff) != nonneg(-dx))
    d.draw_end = false;
  else if (nonneg(-y2diff) == nonneg(dy))
    d.draw_end = true;
  else {
    const float yintersect = fracf(v2.y) + x2diff * dydx;
    d.draw_end = yintersect < 1.0f && yintersect > 0.0f;
  }
  if (dx < 0.0f) {
    d.swap = true;
    if ((x1diff <= 0.f) != d.draw_start) {  // left edge
      d.a_offset_end = -x1diff - 0.5f;
      d.b_offset_end = d.a_offset_end * dydx;
    }
    // right edge. 22.3.6: an end exactly on a pixel column (x2diff == 0) counts as drawn (">="),
    // so it moves back half a pixel; 23.2: ">" (§8.3).
    if ((sign_tests ? x2diff > 0.f : x2diff >= 0.f) != d.draw_end) {
      d.a_offset = -x2diff - 0.5f;
      d.b_offset = d.a_offset * dydx;
    }
  } else {
    if ((x1diff > 0.f) != d.draw_start) {  // right edge
      d.a_offset = -x1diff + 0.5f;
      d.b_offset = d.a_offset * dydx;
    }
    if ((x2diff <= 0.f) != d.draw_end) {  // left edge
      d.a_offset_end = -x2diff + 0.5f;
      d.b_offset_end = d.a_offset_end * dydx;
    }
  }
  return d;
}

DiamondExit diamond_exit_y_major(Endpoint v1, Endpoint v2, float dx, float dy, bool sign_tests) {
  DiamondExit d;
  const float x1diff = v1.x - std::floor(v1.x) - 0.5f, y1diff = v1.y - std::floor(v1.y) - 0.5f;
  float x2diff = v2.x - std::floor(v2.x) - 0.5f;
  const float y2diff = v2.y - std::floor(v2.y) - 0.5f;
  const float dxdy = dx / dy;
  if (x2diff == -0.5f && dx < 0.0f) x2diff = 0.5f;
  if (std::fabs(x1diff) + std::fabs(y1diff) < 0.5f)
    d.draw_start = true;
  else if (nonneg(-y1diff) == nonneg(dy))
    d.draw_start = false;
  else if (nonneg(x1diff) != nonneg(-dx))
    d.draw_start = true;
  else {
    const float xintersect = fracf(v1.x) + y1diff * dxdy;
    d.draw_start = xintersect < 1.0f && xintersect > 0.0f;
  }
  if (std::fabs(x2diff) + std::fabs(y2diff) < 0.5f)
    d.draw_end = false;
  else if (nonneg(-y2diff) != nonneg(dy))
    d.draw_end = false;
  else if (nonneg(x2diff) == nonneg(-dx))
    d.draw_end = true;
  else {
    const float xintersect = fracf(v2.x) + y2diff * dxdy;
    d.draw_end = xintersect < 1.0f && xintersect >= 0.0f;  // ">=" here, ">" in the x-major branch
  }
  if (dy > 0.0f) {
    d.swap = true;
    // bottom edge. 22.3.6: a start exactly on a pixel row (y1diff == 0) counts as already drawn
    // (">="); 23.2: ">" (bottom_edge_rule 0, §8.3). The end test is "<=" in both.
    if ((sign_tests ? y1diff > 0.f : y1diff >= 0.f) != d.draw_start) {
      d.a_offset_end = -y1diff + 0.5f;
      d.b_offset_end = d.a_offset_end * dxdy;
    }
    if ((y2diff <= 0.f) != d.draw_end) {  // top edge
      d.a_offset = -y2diff + 0.5f;
      d.b_offset = d.a_offset * dxdy;
    }
  } else {
    // top edge. 22.3.6: y1diff == 0 counts as not drawn ("<"); 23.2: "<=".
    if ((sign_tests ? y1diff <= 0.f : y1diff < 0.f) != d.draw_start) {
      d.a_offset = -y1diff - 0.5f;
      d.b_offset = d.a_offset * dxdy;
    }
    // bottom edge. 22.3.6: y2diff == 0 counts as drawn (">="); 23.2: ">".
    if ((sign_tests ? y2diff > 0.f : y2diff >= 0.f) != d.draw_end) {
      d.a_offset_end = -y2diff - 0.5f;
      d.b_offset_end = d.a_offset_end * dxdy;
    }
  }
  return d;
}

// The Bresenham parallelogram: end edges perpendicular to the major axis, `width` px long (§5.4).
std::optional<Quad> bresenham_quad(const LineSnap& snap, Endpoint v1, Endpoint v2, bool x_major, const DiamondExit& d,
                                   float width, float pixel_offset) {
  const std::optional<int32_t> width_pixels = snap.round(width);  // "interpreted as integer"
  if (!width_pixels) return std::nullopt;
  const int64_t half_width = int64_t(*width_pixels) * kFixedOne / 2;
  if (d.swap) std::swap(v1, v2);
  const float x_offset = x_major ? d.a_offset : d.b_offset, y_offset = x_major ? d.b_offset : d.a_offset;
  const float x_offset_end = x_major ? d.a_offset_end : d.b_offset_end;
  const float y_offset_end = x_major ? d.b_offset_end : d.a_offset_end;
  const auto x1 = snap(v1.x + x_offset - pixel_offset), x2 = snap(v2.x + x_offset_end - pixel_offset);
  const auto y1 = snap(v1.y + y_offset - pixel_offset), y2 = snap(v2.y + y_offset_end - pixel_offset);
  if (!x1 || !x2 || !y1 || !y2) return std::nullopt;
  const int64_t hx = x_major ? 0 : half_width, hy = x_major ? half_width : 0;
  return Quad{{snap.sub(*x1, hx), snap.sub(*x2, hx), snap.add(*x2, hx), snap.add(*x1, hx)},
              {snap.sub(*y1, hy), snap.sub(*y2, hy), snap.add(*y2, hy), snap.add(*y1, hy)}};
}

// try_setup_line: x0 = (min + 255) >> 8, x1 = ((max + 255) >> 8) - 1.
PixelRect line_bbox(const Quad& q) {
  const auto [min_x, max_x] = std::minmax_element(q.x.begin(), q.x.end());
  const auto [min_y, max_y] = std::minmax_element(q.y.begin(), q.y.end());
  return PixelRect{int32_t((*min_x + kFixedOne - 1) >> kFixedOrder), int32_t((*min_y + kFixedOne - 1) >> kFixedOrder),
                   int32_t(((*max_x + kFixedOne - 1) >> kFixedOrder) - 1),
                   int32_t(((*max_y + kFixedOne - 1) >> kFixedOrder) - 1)};
}

// The corners as int32 (Mesa's int), whatever their size: a quad past the direct range.
std::array<FixedPoint, 4> wrapped_corners(const Quad& q) {
  std::array<FixedPoint, 4> corners;
  for (size_t i = 0; i < 4; ++i) corners[i] = FixedPoint{Fixed24_8{int32_t(q.x[i])}, Fixed24_8{int32_t(q.y[i])}};
  return corners;
}

// The binned coverage of a placed line past the direct range: its four planes and the scissor
// planes place_in_region added (binned_triangle.hpp).
std::shared_ptr<const BinnedTriangle> bin_placed_line(const RasterPrimitive& raster, const PixelRect& region,
                                                      const PixelRect& framebuffer, bool multisample) {
  std::array<LpPlane, 8> planes{};
  const std::array<LpPlane, 4> edges = lp_line_planes(raster.vertex_fixed);
  std::copy(edges.begin(), edges.end(), planes.begin());
  for (uint32_t i = 4; i < raster.planes.count; ++i) planes[i] = lp_scissor_plane(raster.planes.plane[i]);
  return std::make_shared<const BinnedTriangle>(
      bin_triangle(planes, raster.planes.count, raster.bbox, region, framebuffer, multisample));
}

std::optional<std::array<FixedPoint, 4>> quad_corners(const Quad& q) {
  std::array<FixedPoint, 4> corners;
  for (size_t i = 0; i < 4; ++i) {
    const auto x = Fixed24_8::from_wide(q.x[i]), y = Fixed24_8::from_wide(q.y[i]);
    if (!x || !y) return std::nullopt;
    corners[i] = FixedPoint{*x, *y};
  }
  return corners;
}

}  // namespace

bool line_rasterizes_per_sample(const SetupContext& ctx) {
  return ctx.multisample && ctx.state->line_mode != LineMode::Bresenham;
}

LineSetup setup_line(const std::array<WindowVertex, 2>& window, uint32_t owner, const SetupContext& ctx) {
  LineSetup setup;
  const RasterState& state = *ctx.state;
  const Endpoint v1{window[0].x, window[0].y}, v2{window[1].x, window[1].y};
  const float dx = v1.x - v2.x, dy = v1.y - v2.y;
  const float area = dx * dx + dy * dy;
  if (area == 0) {
    setup.fate = SetupFate::Degenerate;
    return setup;
  }
  const float one_over_area = 1.0f / area;
  const bool per_sample = line_rasterizes_per_sample(ctx);
  const float snap_offset = per_sample ? 0.0f : kHalfPixelCenter;  // setup->multisample ? 0 : pixel_offset
  const LineSnap snap{ctx.rules.has(LavapipeRule::LineRoundHalfToEven)};
  float dx_eff = dx, dy_eff = dy;
  std::optional<Quad> quad;
  if (state.line_mode == LineMode::Bresenham) {
    const float width = 1.0f > state.line_width ? 1.0f : state.line_width;  // MAX2(1.0, line_width)
    setup.x_major = std::fabs(dx) >= std::fabs(dy);
    const bool sign_tests = ctx.rules.has(LavapipeRule::BresenhamEndSignTests);
    const DiamondExit d = setup.x_major ? diamond_exit_x_major(v1, v2, dx, dy, sign_tests)
                                        : diamond_exit_y_major(v1, v2, dx, dy, sign_tests);
    setup.draw_start = d.draw_start;
    setup.draw_end = d.draw_end;
    if (setup.x_major) {  // "the preferred wide-lines formula" for the depth gradient
      const float dydx = dy / dx;
      dx_eff = dx * (1.0f + dydx * dydx);
      dy_eff = 0.0f;
    } else {
      const float dxdy = dx / dy;
      dx_eff = 0.0f;
      dy_eff = dy * (1.0f + dxdy * dxdy);
    }
    quad = bresenham_quad(snap, v1, v2, setup.x_major, d, width, snap_offset);
  } else {
    quad = rectangular_quad(snap, v1, v2, dx, dy, area, state.line_width, snap_offset);
  }
  std::optional<std::array<FixedPoint, 4>> corners = quad ? quad_corners(*quad) : std::nullopt;
  // From 23.2 a line is drawn unclipped in x and y (§8.2), so its quad may leave the range where
  // the plane test is llvmpipe's: it then follows llvmpipe's wrapping arithmetic (§7.5).
  const bool binned = quad && snap.lrintf && (!corners || !quad_in_direct_range(*corners));
  if (binned) corners = wrapped_corners(*quad);
  if (!corners) {
    setup.fate = SetupFate::NonFinite;
    return setup;
  }
  setup.bbox = binned ? wrapped_line_bbox(*corners) : line_bbox(*quad);
  RasterPrimitive& raster = setup.raster;
  raster.owner = owner;
  raster.is_line = true;
  raster.per_sample = per_sample;
  raster.edge_count = 4;
  raster.vertex_fixed = *corners;
  for (size_t i = 0; i < 4; ++i)
    raster.planes.push(binned ? EdgePlane{} : make_edge((*corners)[i], (*corners)[(i + 1) % 4], ctx.methods.tie_break));
  if (!place_in_region(raster, setup.bbox, ctx.region, ctx.framebuffer, per_sample, binned,
                       ctx.rules.has(LavapipeRule::NoMsaaRegionLeak))) {
    setup.fate = SetupFate::OutsideRegion;
    return setup;
  }
  if (binned) {
    refuse_if_overflow_reworked(ctx.rules);
    raster.binned = bin_placed_line(raster, ctx.region, ctx.framebuffer, per_sample);
  }
  if (ctx.depth_plane_wanted()) {  // linear_coef uses setup->pixel_offset (§5.5)
    raster.has_depth = ctx.depth_active();
    // setup->pixel_offset: 0.5, or from 25.3 0 when the line is multisampled (§8.5)
    const bool offset_zero = per_sample && ctx.rules.has(LavapipeRule::MsaaLineDepthAtCentre);
    raster.depth =
        line_depth_plane(window[0], window[1], dx_eff, dy_eff, one_over_area, offset_zero ? 0.0f : kHalfPixelCenter);
  }
  return setup;
}

}  // namespace rastercmp::cpu
