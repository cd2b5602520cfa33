#include "cpu_raster/methods/fill_polygon_rule.hpp"

#include <algorithm>

namespace rastercmp::methods {

namespace {

struct RowCrossing {
  double x = 0;
  int direction = 0;  // +1 edge going up (y increasing), -1 going down
};

std::vector<RowCrossing> row_crossings(const Polygon2& polygon, double y_sample) {
  std::vector<RowCrossing> crossings;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = polygon[i], b = polygon[(i + 1) % n];
    if (a.y == b.y) continue;
    const Vec2 lo = a.y < b.y ? a : b, hi = a.y < b.y ? b : a;
    if (!(lo.y <= y_sample && y_sample < hi.y)) continue;
    crossings.push_back({lo.x + (y_sample - lo.y) * (hi.x - lo.x) / (hi.y - lo.y), a.y < b.y ? 1 : -1});
  }
  std::sort(crossings.begin(), crossings.end(), [](const RowCrossing& l, const RowCrossing& r) { return l.x < r.x; });
  return crossings;
}

bool inside(int winding, FillRule rule) { return rule == FillRule::EvenOdd ? (winding % 2 != 0) : winding != 0; }

}  // namespace

std::vector<Span> fill_polygon_rule(const Polygon2& polygon, const PolygonFillOptions& options) {
  SpanBuilder spans;
  if (polygon.size() < 3) return spans.take();
  double y_min = polygon[0].y, y_max = polygon[0].y;
  for (const Vec2& v : polygon) {
    y_min = std::min(y_min, v.y);
    y_max = std::max(y_max, v.y);
  }
  const double offset = options.sample_offset;
  const int32_t y_first = std::max(ceil_to_pixel(y_min - offset), options.bounds.y_min);
  for (int32_t y = y_first; y < options.bounds.y_max && double(y) + offset < y_max; ++y) {
    const std::vector<RowCrossing> crossings = row_crossings(polygon, double(y) + offset);
    int winding = 0;
    for (size_t k = 0; k + 1 < crossings.size(); ++k) {
      winding += crossings[k].direction;
      if (!inside(winding, options.rule)) continue;
      // Samples x + offset in [x_k, x_k+1): x from ceil(x_k - offset) to ceil(x_k+1 - offset).
      add_clamped(spans, options.bounds, y, ceil_to_pixel(crossings[k].x - offset),
                  ceil_to_pixel(crossings[k + 1].x - offset));
    }
  }
  return spans.take();
}

}  // namespace rastercmp::methods
