#include "cpu_raster/spec/line_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rastercmp::cpu::spec {
namespace {

using glm::dvec2;

// Below this length (pixels) a segment has no direction to speak of.
constexpr double kMinLinePx = 1e-6;

// Rectangle of `width` centred on a→b, both ends pushed out by `extend` along the segment.
Quad rectangle(dvec2 a, dvec2 b, double width, double extend) {
  const dvec2 d = b - a;
  const dvec2 dir = d / std::hypot(d.x, d.y);
  const dvec2 half_normal = dvec2(-dir.y, dir.x) * (0.5 * width);
  const dvec2 a_out = a - dir * extend, b_out = b + dir * extend;
  return {{a_out + half_normal, b_out + half_normal, b_out - half_normal, a_out - half_normal}};
}

// Parallelogram with end edges of length `minor_extent` along the minor axis, ends pushed out by
// `extend` pixels measured along the major axis.
Quad parallelogram(dvec2 a, dvec2 b, double minor_extent, double extend) {
  const dvec2 d = b - a;
  const bool x_major = std::fabs(d.x) >= std::fabs(d.y);
  const dvec2 half_minor = x_major ? dvec2(0, 0.5 * minor_extent) : dvec2(0.5 * minor_extent, 0);
  const dvec2 push = d * (extend / (x_major ? std::fabs(d.x) : std::fabs(d.y)));
  const dvec2 a_out = a - push, b_out = b + push;
  return {{a_out + half_minor, b_out + half_minor, b_out - half_minor, a_out - half_minor}};
}

Quad square(dvec2 centre, double half) {
  return {{centre + dvec2(-half, -half), centre + dvec2(half, -half), centre + dvec2(half, half),
           centre + dvec2(-half, half)}};
}

double cross(dvec2 u, dvec2 v) { return u.x * v.y - u.y * v.x; }

// Smallest and largest signed distance (positive inside) from edge i of the quad over a square of
// half-size `half` around `centre`. A zero-length edge imposes nothing.
struct Reach {
  double lo, hi;
};
Reach edge_reach(const Quad& quad, size_t i, dvec2 centre, double half) {
  const dvec2 p = quad.corner[i], q = quad.corner[(i + 1) % 4];
  const double orientation = cross(quad.corner[1] - quad.corner[0], quad.corner[2] - quad.corner[0]) +
                             cross(quad.corner[2] - quad.corner[0], quad.corner[3] - quad.corner[0]);
  const double length = std::hypot(q.x - p.x, q.y - p.y);
  if (length == 0 || orientation == 0) return {0, 0};
  const dvec2 inward = dvec2(-(q.y - p.y), q.x - p.x) / length * (orientation > 0 ? 1.0 : -1.0);
  const double d = inward.x * (centre.x - p.x) + inward.y * (centre.y - p.y);
  const double spread = half * (std::fabs(inward.x) + std::fabs(inward.y));
  return {d - spread, d + spread};
}

bool square_inside(const Quad& quad, dvec2 centre, double half) {
  for (size_t i = 0; i < 4; ++i)
    if (!(edge_reach(quad, i, centre, half).lo > 0)) return false;
  return true;
}

// Separating axes: the square's (bounds) and the quad's edge normals.
bool square_touches(const Quad& quad, dvec2 centre, double half) {
  double x_min = quad.corner[0].x, x_max = x_min, y_min = quad.corner[0].y, y_max = y_min;
  for (const dvec2& c : quad.corner) {
    x_min = std::min(x_min, c.x);
    x_max = std::max(x_max, c.x);
    y_min = std::min(y_min, c.y);
    y_max = std::max(y_max, c.y);
  }
  if (centre.x + half < x_min || centre.x - half > x_max || centre.y + half < y_min || centre.y - half > y_max)
    return false;
  for (size_t i = 0; i < 4; ++i)
    if (edge_reach(quad, i, centre, half).hi < 0) return false;
  return true;
}

// The widths a device may rasterize a line of `width` with (Vulkan "Line Segments": "If an
// unsupported width is requested, the nearest supported width is used instead"; supported widths
// lie lineWidthGranularity apart, at most 1.0 ("Limit Requirements"), and 1.0 is always supported).
// Unknown granularity: the nearest supported width lies within half of 1.0, and no farther than 1.0.
struct WidthRange {
  double lo, hi;
};
WidthRange supported_widths(double width) {
  const double reach = std::min(0.5, std::fabs(width - 1.0));
  return {width - reach, width + reach};
}

}  // namespace

double widest_line_width(float line_width) { return supported_widths(line_width).hi; }

LineShape line_shape(const std::array<glm::dvec2, 2>& pos_window, LineMode mode, float line_width) {
  const dvec2 a = pos_window[0], b = pos_window[1];
  const WidthRange widths = supported_widths(line_width);
  // Bresenham rounds the width to an integer, in a direction the spec leaves open.
  const double width_lo = std::max(1.0, std::floor(widths.lo)), width_hi = std::max(1.0, std::ceil(widths.hi));
  const double widest = mode == LineMode::Bresenham ? width_hi : widths.hi;
  LineShape shape;
  if (std::hypot(b.x - a.x, b.y - a.y) < kMinLinePx) {  // no direction: anything near the point
    shape.may.push_back(square(a, 0.5 * widest));
    return shape;
  }
  const double extend = 0.5 * widest;
  switch (mode) {
    case LineMode::Rectangular:
      shape.must = {rectangle(a, b, widths.lo, 0)};
      shape.may = {rectangle(a, b, widths.hi, extend)};
      break;
    case LineMode::Default:  // strictLines unknown: rectangle or parallelogram
      shape.must = {rectangle(a, b, widths.lo, 0), parallelogram(a, b, widths.lo, 0)};
      shape.may = {rectangle(a, b, widths.hi, extend), parallelogram(a, b, widths.hi, extend)};
      break;
    case LineMode::Bresenham:
      shape.must = {parallelogram(a, b, width_lo, 0)};
      shape.may = {parallelogram(a, b, width_hi, extend)};
      break;
    case LineMode::RectangularSmooth:  // the rectangle, but coverage is an implementation's alpha
      shape.may = {rectangle(a, b, widths.hi, extend)};
      break;
  }
  return shape;
}

Coverage classify_line_box(const LineShape& shape, const PixelSquare& box) {
  const double half = box.half + kLineMarginPx;
  const bool touched = std::any_of(shape.may.begin(), shape.may.end(),
                                   [&](const Quad& q) { return square_touches(q, box.centre, half); });
  if (!touched) return Coverage::None;
  if (shape.must.empty()) return Coverage::Partial;
  const bool inside = std::all_of(shape.must.begin(), shape.must.end(),
                                  [&](const Quad& q) { return square_inside(q, box.centre, half); });
  return inside ? Coverage::Full : Coverage::Partial;
}

PixelBounds may_bounds(const LineShape& shape) {
  PixelBounds b{shape.may[0].corner[0].x, shape.may[0].corner[0].x, shape.may[0].corner[0].y, shape.may[0].corner[0].y};
  for (const Quad& q : shape.may)
    for (const dvec2& c : q.corner) {
      b.x_min = std::min(b.x_min, c.x);
      b.x_max = std::max(b.x_max, c.x);
      b.y_min = std::min(b.y_min, c.y);
      b.y_max = std::max(b.y_max, c.y);
    }
  return {b.x_min - kLineMarginPx, b.x_max + kLineMarginPx, b.y_min - kLineMarginPx, b.y_max + kLineMarginPx};
}

XExtent may_extent_in_band(const LineShape& shape, double y_lo, double y_hi) {
  // A convex polygon cut by a band has its corners among the polygon's corners inside the band and
  // the points where its edges cross the band's two lines.
  XExtent e{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const auto take = [&](double x) {
    e.x_min = std::min(e.x_min, x);
    e.x_max = std::max(e.x_max, x);
  };
  for (const Quad& quad : shape.may)
    for (size_t i = 0; i < 4; ++i) {
      const dvec2 p = quad.corner[i], q = quad.corner[(i + 1) % 4];
      if (p.y >= y_lo && p.y <= y_hi) take(p.x);
      for (const double y : {y_lo, y_hi})
        if ((p.y - y) * (q.y - y) < 0) take(p.x + (q.x - p.x) * ((y - p.y) / (q.y - p.y)));
    }
  return e;
}

IndexSpan line_rows(const LineShape& shape, double half_px, int32_t lo, int32_t hi) {
  const PixelBounds b = may_bounds(shape);
  return {int32_t(std::max(double(lo), std::ceil(b.y_min - half_px - 0.5))),
          int32_t(std::min(double(hi), std::floor(b.y_max + half_px - 0.5)))};
}

IndexSpan line_columns(const LineShape& shape, double half_px, int32_t py, int32_t lo, int32_t hi) {
  const double reach = half_px + kLineMarginPx;  // the grown square's half-size
  const XExtent e = may_extent_in_band(shape, py + 0.5 - reach, py + 0.5 + reach);
  if (e.x_min > e.x_max) return {};
  return {int32_t(std::max(double(lo), std::ceil(e.x_min - reach - 0.5))),
          int32_t(std::min(double(hi), std::floor(e.x_max + reach - 0.5)))};
}

}  // namespace rastercmp::cpu::spec
