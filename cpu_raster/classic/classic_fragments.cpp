#include "cpu_raster/classic/classic_fragments.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "cpu_raster/classic/method_registry.hpp"
#include "cpu_raster/methods/depth_bilinear.hpp"
#include "cpu_raster/methods/fill_edge_function.hpp"
#include "cpu_raster/methods/fill_flood.hpp"
#include "cpu_raster/methods/fill_polygon_rule.hpp"
#include "cpu_raster/methods/fill_scanline_notes.hpp"
#include "cpu_raster/methods/interp_perspective.hpp"
#include "cpu_raster/methods/line_bresenham.hpp"
#include "cpu_raster/methods/line_dda.hpp"
#include "cpu_raster/methods/pseudo_depth.hpp"

namespace rastercmp::cpu::classic {
namespace {

methods::PixelBounds bounds_of(const PixelRect& region) {
  return methods::PixelBounds{region.x0, region.y0, region.x1 + 1, region.y1 + 1};
}

// The set-up's planes at the pixel centre (single sample, docs/lavapipe-rules.md §2.4).
std::vector<methods::Span> exact_spans(const RasterPrimitive& raster) {
  methods::SpanBuilder builder;
  for (int32_t py = raster.visit.y0; py <= raster.visit.y1; ++py)
    for (int32_t px = raster.visit.x0; px <= raster.visit.x1; ++px) {
      const SamplePoint point = sample_point(px, py, 0, false);
      if (first_failing_plane(raster.planes, point.x_fixed, point.y_fixed) < 0) builder.add(py, px, px + 1);
    }
  return builder.take();
}

methods::Polygon2 window_polygon(const ClassicPrimitive& p, double shift) {
  methods::Polygon2 polygon;
  for (size_t k = 0; k < 3; ++k) polygon.push_back({double(p.window[k].x) + shift, double(p.window[k].y) + shift});
  return polygon;
}

// The pixel holding a window point.
methods::PixelXY pixel_of(const WindowVertex& v) { return {int32_t(std::floor(v.x)), int32_t(std::floor(v.y))}; }

}  // namespace

FloodTrace flood_trace(const ClassicPrimitive& p, const PixelRect& region) {
  FloodTrace trace;
  int32_t x0 = region.x1, y0 = region.y1, x1 = region.x0, y1 = region.y0;  // the outline's pixel box ∩ region
  for (size_t k = 0; k < 3; ++k) {
    const methods::PixelXY v = pixel_of(p.window[k]);
    x0 = std::min(x0, v.x), y0 = std::min(y0, v.y), x1 = std::max(x1, v.x), y1 = std::max(y1, v.y);
  }
  x0 = std::max(x0, region.x0), y0 = std::max(y0, region.y0), x1 = std::min(x1, region.x1),
  y1 = std::min(y1, region.y1);
  if (x0 > x1 || y0 > y1) return trace;
  methods::CellGrid grid{x1 - x0 + 1, y1 - y0 + 1, {}};
  grid.cells.assign(size_t(grid.width) * size_t(grid.height), kFloodEmpty);
  trace.origin = {x0, y0};
  for (size_t k = 0; k < 3; ++k)  // the outline, Bresenham between the vertices' pixels
    for (const methods::PixelXY& q : methods::line_bresenham(pixel_of(p.window[k]), pixel_of(p.window[(k + 1) % 3]))) {
      const methods::PixelXY cell{q.x - x0, q.y - y0};
      if (grid.contains(cell)) grid.cells[size_t(cell.y) * size_t(grid.width) + size_t(cell.x)] = kFloodOutline;
    }
  // The seed: the centroid's pixel when it is inside and not on the outline, else the first
  // such pixel in row order whose centre lies inside the float triangle.
  const methods::Polygon2 triangle{
      {p.window[0].x, p.window[0].y}, {p.window[1].x, p.window[1].y}, {p.window[2].x, p.window[2].y}};
  const auto usable = [&](methods::PixelXY cell) {
    return grid.contains(cell) && grid.at(cell) == kFloodEmpty &&
           methods::winding_number(triangle, {cell.x + x0 + 0.5, cell.y + y0 + 0.5}) != 0;
  };
  const methods::PixelXY centroid{
      int32_t(std::floor((double(p.window[0].x) + p.window[1].x + p.window[2].x) / 3)) - x0,
      int32_t(std::floor((double(p.window[0].y) + p.window[1].y + p.window[2].y) / 3)) - y0};
  std::optional<methods::PixelXY> seed;
  if (usable(centroid)) seed = centroid;
  for (int32_t y = 0; y < grid.height && !seed; ++y)
    for (int32_t x = 0; x < grid.width && !seed; ++x)
      if (usable({x, y})) seed = methods::PixelXY{x, y};
  if (seed) {
    trace.seed = methods::PixelXY{seed->x + x0, seed->y + y0};
    methods::FloodFillResult filled = methods::flood_fill(grid, *seed, kFloodFilled);
    trace.filled = filled.filled;
    grid = std::move(filled.grid);
  }
  trace.grid = std::move(grid);
  return trace;
}

namespace {

std::vector<methods::Span> flood_spans(const ClassicPrimitive& p, const PixelRect& region) {
  const FloodTrace trace = flood_trace(p, region);
  methods::SpanBuilder builder;
  for (int32_t y = 0; y < trace.grid.height; ++y)
    for (int32_t x = 0; x < trace.grid.width; ++x)
      if (trace.grid.at({x, y}) != kFloodEmpty)
        builder.add(y + trace.origin.y, x + trace.origin.x, x + trace.origin.x + 1);
  return builder.take();
}

std::vector<methods::Span> coverage_spans(const ClassicPrimitive& p, FillMethod fill, const PixelRect& region) {
  const methods::PixelBounds bounds = bounds_of(region);
  switch (fill) {
    case FillMethod::Exact: return exact_spans(p.raster);
    case FillMethod::Scanline: return methods::fill_scanline_notes(window_polygon(p, -0.5), bounds);
    case FillMethod::FloatEdge: {
      const std::array<methods::Vec2f, 3> pos_window{methods::Vec2f{p.window[0].x, p.window[0].y},
                                                     methods::Vec2f{p.window[1].x, p.window[1].y},
                                                     methods::Vec2f{p.window[2].x, p.window[2].y}};
      return methods::fill_triangle_edge_function(pos_window, methods::EdgeTieRule::None, bounds);
    }
    case FillMethod::EvenOdd:
    case FillMethod::Winding: {
      const methods::FillRule rule =
          fill == FillMethod::EvenOdd ? methods::FillRule::EvenOdd : methods::FillRule::NonZero;
      return methods::fill_polygon_rule(window_polygon(p, 0), {rule, 0.5, bounds});
    }
    case FillMethod::Flood: return flood_spans(p, region);
  }
  return {};
}

std::vector<methods::PixelXY> line_pixels(const ClassicPrimitive& p, LineMethod line) {
  const auto [p0, p1] = line_method_endpoints(p);
  return line == LineMethod::Dda ? methods::line_dda(p0, p1) : methods::line_bresenham(p0, p1);
}

// The exact path's tail after interpolation: bias, clamps, conversion (§3.4-§3.5), reached through
// sample_depth with a constant plane so the rounding is the same.
uint32_t finish_depth(const ClassicPrimitive& p, float z) {
  const DepthPlane constant{z, 0, 0};
  return sample_depth(constant, p.raster.offset.offset, 0, 0, p.depth.range, p.depth.format, false).raw;
}

uint32_t plane_depth_raw(const ClassicPrimitive& p, int32_t px, int32_t py, bool fma) {
  const SamplePoint point = sample_point(px, py, 0, false);
  return sample_depth(p.raster.depth, p.raster.offset.offset, point.x, point.y, p.depth.range, p.depth.format, fma).raw;
}

// The eye distance w at the pixel centre: 1/w is affine in window space (lines: along the segment).
double eye_distance_at(const ClassicPrimitive& p, methods::Vec2 centre) {
  if (p.is_line) {
    const methods::Vec2 a{p.window[0].x, p.window[0].y}, b{p.window[1].x, p.window[1].y};
    const double length2 = methods::dot(b - a, b - a);
    const double t = length2 > 0 ? std::clamp(methods::dot(centre - a, b - a) / length2, 0.0, 1.0) : 0.0;
    return 1 / ((1 - t) / double(p.w_clip[0]) + t / double(p.w_clip[1]));
  }
  const std::array<methods::Vec2, 3> pos_window{methods::Vec2{p.window[0].x, p.window[0].y},
                                                methods::Vec2{p.window[1].x, p.window[1].y},
                                                methods::Vec2{p.window[2].x, p.window[2].y}};
  const std::array<double, 3> l = methods::barycentric_window(pos_window, centre);
  double inv_w = 0;
  for (size_t k = 0; k < 3; ++k) inv_w += l[k] / double(p.w_clip[k]);
  return 1 / inv_w;
}

}  // namespace

std::array<methods::PixelXY, 2> line_method_endpoints(const ClassicPrimitive& p) {
  return {pixel_of(p.window[0]), pixel_of(p.window[1])};
}

PerspectiveTrace perspective_trace(const ClassicPrimitive& p, int32_t px, int32_t py) {
  const std::array<methods::Vec2, 3> pos_window{methods::Vec2{p.window[0].x, p.window[0].y},
                                                methods::Vec2{p.window[1].x, p.window[1].y},
                                                methods::Vec2{p.window[2].x, p.window[2].y}};
  const std::array<double, 3> z_window{p.window[0].z, p.window[1].z, p.window[2].z};
  const std::array<double, 3> w_clip{p.w_clip[0], p.w_clip[1], p.w_clip[2]};
  PerspectiveTrace trace;
  trace.lambda = methods::barycentric_window(pos_window, {px + 0.5, py + 0.5});
  for (size_t k = 0; k < 3; ++k) {
    trace.inv_w[k] = 1 / w_clip[k];
    trace.inv_w_at += trace.lambda[k] / w_clip[k];
  }
  trace.z_linear = methods::interpolate_linear(trace.lambda, z_window);
  trace.z_perspective = methods::interpolate_perspective(trace.lambda, z_window, w_clip);
  return trace;
}

double pseudo_depth_value(const ClassicPrimitive& p, double far_distance, int32_t px, int32_t py) {
  const double w = eye_distance_at(p, {px + 0.5, py + 0.5});
  // Eye z is -w (camera looking down -z); pz = 1 at near, -1 at far; stored as (1 - pz) / 2.
  return (1 - methods::pseudo_depth(-w, -kPseudoDepthNear, -far_distance)) / 2;
}

uint32_t fragment_depth_raw(const ClassicPrimitive& p, const ClassicMethods& chosen, int32_t px, int32_t py) {
  const DepthMethod method = chosen.depth;
  if (method == DepthMethod::PseudoDepth)
    return finish_depth(p, float(pseudo_depth_value(p, chosen.pseudo_far, px, py)));
  if (method == DepthMethod::NoFma) return plane_depth_raw(p, px, py, false);
  if (method == DepthMethod::Exact || p.is_line) return plane_depth_raw(p, px, py, p.depth.fma);
  const methods::Vec2 centre{px + 0.5, py + 0.5};
  if (method == DepthMethod::Bilinear) {
    std::array<methods::Vec3, 3> triangle;
    for (size_t k = 0; k < 3; ++k) triangle[k] = {p.window[k].x, p.window[k].y, p.window[k].z};
    const std::optional<double> z = methods::bilinear_depth_in_triangle(triangle, centre);
    // A pixel the fill covers whose centre lies outside the float triangle (snapping, ties) has
    // no bilinear value; it takes the plane's.
    return z ? finish_depth(p, float(*z)) : plane_depth_raw(p, px, py, p.depth.fma);
  }
  return finish_depth(p, float(perspective_trace(p, px, py).z_perspective));
}

void for_each_fragment(const ClassicPrimitive& p, const ClassicMethods& chosen, const PixelRect& region,
                       const FragmentSink& sink) {
  const auto emit = [&](int32_t x, int32_t y) {
    if (!region.contains(x, y)) return;
    Fragment fragment{x, y, 0};
    if (p.depth.active) fragment.depth_raw = fragment_depth_raw(p, chosen, x, y);
    sink(fragment);
  };
  if (p.is_line && chosen.line != LineMethod::Exact) {
    for (const methods::PixelXY& pixel : line_pixels(p, chosen.line)) emit(pixel.x, pixel.y);
    return;
  }
  const FillMethod fill = p.is_line ? FillMethod::Exact : chosen.fill;
  for (const methods::Span& span : coverage_spans(p, fill, region))
    for (int32_t x = span.x_begin; x < span.x_end; ++x) emit(x, span.y);
}

}  // namespace rastercmp::cpu::classic
