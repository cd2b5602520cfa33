#include "cpu_raster/methods/fill_scanline_notes.hpp"

#include <algorithm>
#include <cmath>

namespace rastercmp::methods {

std::vector<double> scanline_intersections_notes(const Polygon2& polygon, double y) {
  std::vector<double> xs;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = polygon[i], b = polygon[(i + 1) % n];
    if (a.y == b.y) continue;  // ignore horizontal boundaries
    const Vec2 lo = a.y < b.y ? a : b, hi = a.y < b.y ? b : a;
    if (!(lo.y <= y && y < hi.y)) continue;  // closed at the bottom, open at the top
    xs.push_back(lo.x + (y - lo.y) * (hi.x - lo.x) / (hi.y - lo.y));
  }
  std::sort(xs.begin(), xs.end());
  return xs;
}

std::vector<Span> fill_scanline_notes(const Polygon2& polygon, const PixelBounds& bounds) {
  SpanBuilder spans;
  if (polygon.size() < 3) return spans.take();
  double y_min = polygon[0].y, y_max = polygon[0].y;
  for (const Vec2& v : polygon) {
    y_min = std::min(y_min, v.y);
    y_max = std::max(y_max, v.y);
  }
  const int32_t y_first = std::max(ceil_to_pixel(y_min), bounds.y_min);
  for (int32_t y = y_first; y < bounds.y_max && double(y) < y_max; ++y) {
    const std::vector<double> xs = scanline_intersections_notes(polygon, double(y));
    for (size_t k = 0; k + 1 < xs.size(); k += 2) {  // every pair of intersections
      add_clamped(spans, bounds, y, ceil_to_pixel(xs[k]), ceil_to_pixel(xs[k + 1]));
    }
  }
  return spans.take();
}

}  // namespace rastercmp::methods
