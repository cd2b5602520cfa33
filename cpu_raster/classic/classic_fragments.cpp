#include "cpu_raster/classic/classic_fragments.hpp"

#include <cmath>
#include <optional>
#include <vector>

#include "cpu_raster/methods/depth_bilinear.hpp"
#include "cpu_raster/methods/fill_edge_function.hpp"
#include "cpu_raster/methods/fill_polygon_rule.hpp"
#include "cpu_raster/methods/fill_scanline_notes.hpp"
#include "cpu_raster/methods/interp_perspective.hpp"
#include "cpu_raster/methods/line_bresenham.hpp"
#include "cpu_raster/methods/line_dda.hpp"

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
  }
  return {};
}

// The pixel holding a window point.
methods::PixelXY pixel_of(const WindowVertex& v) { return {int32_t(std::floor(v.x)), int32_t(std::floor(v.y))}; }

std::vector<methods::PixelXY> line_pixels(const ClassicPrimitive& p, LineMethod line) {
  const methods::PixelXY p0 = pixel_of(p.window[0]), p1 = pixel_of(p.window[1]);
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

}  // namespace

uint32_t fragment_depth_raw(const ClassicPrimitive& p, DepthMethod method, int32_t px, int32_t py) {
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
  const std::array<methods::Vec2, 3> pos_window{methods::Vec2{p.window[0].x, p.window[0].y},
                                                methods::Vec2{p.window[1].x, p.window[1].y},
                                                methods::Vec2{p.window[2].x, p.window[2].y}};
  const std::array<double, 3> z_window{p.window[0].z, p.window[1].z, p.window[2].z};
  const std::array<double, 3> w_clip{p.w_clip[0], p.w_clip[1], p.w_clip[2]};
  const double z = methods::interpolate_perspective(methods::barycentric_window(pos_window, centre), z_window, w_clip);
  return finish_depth(p, float(z));
}

void for_each_fragment(const ClassicPrimitive& p, const ClassicMethods& chosen, const PixelRect& region,
                       const FragmentSink& sink) {
  const auto emit = [&](int32_t x, int32_t y) {
    if (!region.contains(x, y)) return;
    Fragment fragment{x, y, 0};
    if (p.depth.active) fragment.depth_raw = fragment_depth_raw(p, chosen.depth, x, y);
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
