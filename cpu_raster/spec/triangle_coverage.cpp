#include "cpu_raster/spec/triangle_coverage.hpp"

#include <algorithm>

namespace rastercmp::cpu::spec {
namespace {

// cross(b - a, c - a): positive when a, b, c turn counter-clockwise in a y-up frame.
Wide cross(GridPoint a, GridPoint b, GridPoint c) {
  return (Wide(b.x) - a.x) * (Wide(c.y) - a.y) - (Wide(b.y) - a.y) * (Wide(c.x) - a.x);
}

// Sign of cross(v1 - v0, v2 - v0) shared by all 64 corner placements of the cells, else 0. The
// cross product is multilinear in the six coordinates, so the corners bound the whole cells.
int certain_cross_sign(const std::array<SnapCell, 3>& cells) {
  bool positive = false, negative = false, zero = false;
  for (int k = 0; k < 64; ++k) {
    const Wide c = cross(cells[0].corner(k & 3), cells[1].corner((k >> 2) & 3), cells[2].corner(k >> 4));
    positive |= c > 0;
    negative |= c < 0;
    zero |= c == 0;
  }
  if (zero || (positive && negative)) return 0;
  return positive ? 1 : -1;
}

// Andrew's monotone chain; collinear points are dropped, so 1 or 2 points may remain.
std::vector<GridPoint> convex_hull(std::vector<GridPoint> points) {
  std::sort(points.begin(), points.end(),
            [](GridPoint p, GridPoint q) { return p.x < q.x || (p.x == q.x && p.y < q.y); });
  points.erase(
      std::unique(points.begin(), points.end(), [](GridPoint p, GridPoint q) { return p.x == q.x && p.y == q.y; }),
      points.end());
  if (points.size() < 3) return points;
  std::vector<GridPoint> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

Wide floor_div(Wide n, Wide d) {  // d > 0
  const Wide q = n / d;
  return (n % d != 0 && n < 0) ? q - 1 : q;
}

Wide ceil_div(Wide n, Wide d) { return -floor_div(-n, d); }

// Pixel columns px (box centre x = px*one + one/2 in row `box`) where the value of `e` over the
// box (its minimum when `strictly_positive_min`, else its maximum) is > 0, resp. >= 0: a half-line,
// everything or nothing. In the box, min/max = a*one*px + k with k independent of px.
struct Span {
  Wide first, last;
};
constexpr Wide kAll = Wide(1) << 100;

Span columns_where(const LineEquation& e, const ToleranceBox& row_box, int64_t one, bool strictly_positive_min) {
  const Wide spread = Wide(row_box.half) * ((e.a < 0 ? -e.a : e.a) + (e.b < 0 ? -e.b : e.b));
  const Wide k = e.a * (one / 2) + e.b * row_box.cy + e.c + (strictly_positive_min ? -spread : spread);
  const Wide slope = e.a * one;
  if (strictly_positive_min) {  // slope*px + k > 0
    if (slope == 0) return k > 0 ? Span{-kAll, kAll} : Span{1, 0};
    if (slope > 0) return {floor_div(-k, slope) + 1, kAll};
    return {-kAll, ceil_div(k, -slope) - 1};
  }
  // slope*px + k >= 0
  if (slope == 0) return k >= 0 ? Span{-kAll, kAll} : Span{1, 0};
  if (slope > 0) return {ceil_div(-k, slope), kAll};
  return {-kAll, floor_div(k, -slope)};
}

void narrow(Span& span, const Span& by) {
  span.first = std::max(span.first, by.first);
  span.last = std::min(span.last, by.last);
}

}  // namespace

SnappedTriangle snap_triangle(const std::array<glm::dvec2, 3>& pos_window, uint32_t bits) {
  SnappedTriangle t;
  for (size_t i = 0; i < 3; ++i) t.cell[i] = snap_cell(pos_window[i].x, pos_window[i].y, bits);
  // Facing with one more grid unit of slack than snapping needs, for the device's own float
  // arithmetic before it snaps (the CTS's "accumulated errors").
  const std::array<SnapCell, 3> wide = {t.cell[0].widened(1), t.cell[1].widened(1), t.cell[2].widened(1)};
  const int cross_sign = certain_cross_sign(wide);
  t.area_sign = -cross_sign;  // a = -1/2 cross(v1 - v0, v2 - v0)
  if (cross_sign != 0) {
    for (int i = 0; i < 3; ++i) {
      const SnapCell& from = t.cell[size_t(i)];
      const SnapCell& to = t.cell[size_t((i + 1) % 3)];
      for (int v = 0; v < 16; ++v) {
        // The third vertex is left of from→to (y up) exactly when cross > 0.
        const LineEquation e = line_through(from.corner(v & 3), to.corner(v >> 2));
        t.edge[size_t(i)][size_t(v)] = cross_sign > 0 ? e : negated(e);
      }
    }
  }
  std::vector<GridPoint> corners;
  for (const SnapCell& cell : t.cell)
    for (int k = 0; k < 4; ++k) corners.push_back(cell.corner(k));
  t.hull = convex_hull(corners);
  t.x_min = t.x_max = t.hull[0].x;
  t.y_min = t.y_max = t.hull[0].y;
  for (const GridPoint& p : t.hull) {
    t.x_min = std::min(t.x_min, p.x);
    t.x_max = std::max(t.x_max, p.x);
    t.y_min = std::min(t.y_min, p.y);
    t.y_max = std::max(t.y_max, p.y);
  }
  return t;
}

bool box_inside_edge(const SnappedTriangle& triangle, int edge, const ToleranceBox& box) {
  if (triangle.area_sign == 0) return false;
  for (const LineEquation& variant : triangle.edge[size_t(edge)])
    if (min_over_box(variant, box) <= 0) return false;
  return true;
}

// Separating axis test between the box and the convex hull: the box's own axes, then the hull's
// edge normals. Exact for convex shapes; touching counts as overlapping.
bool box_outside(const SnappedTriangle& triangle, const ToleranceBox& box) {
  if (box.cx + box.half < triangle.x_min || box.cx - box.half > triangle.x_max || box.cy + box.half < triangle.y_min ||
      box.cy - box.half > triangle.y_max)
    return true;
  const size_t n = triangle.hull.size();
  if (n < 2) return false;  // a point: the bounds above decide
  for (size_t i = 0; i < n; ++i) {
    const LineEquation inside_left = line_through(triangle.hull[i], triangle.hull[(i + 1) % n]);
    if (max_over_box(inside_left, box) < 0) return true;
  }
  return false;
}

Coverage classify_box(const SnappedTriangle& triangle, const ToleranceBox& box) {
  if (box_outside(triangle, box)) return Coverage::None;
  for (int edge = 0; edge < 3; ++edge)
    if (!box_inside_edge(triangle, edge, box)) return Coverage::Partial;
  return Coverage::Full;
}

RowSpans row_spans(const SnappedTriangle& triangle, int32_t py, uint32_t bits, bool multisample) {
  const ToleranceBox row_box = pixel_box(0, py, bits, multisample);
  const int64_t one = int64_t(1) << bits;
  RowSpans spans;
  if (row_box.cy + row_box.half < triangle.y_min || row_box.cy - row_box.half > triangle.y_max) return spans;
  const PixelSpan bounds = pixels_touching(triangle.x_min, triangle.x_max, bits, multisample);
  Span touch{bounds.first, bounds.last};
  const size_t n = triangle.hull.size();
  if (n >= 2)
    for (size_t i = 0; i < n; ++i)
      narrow(touch, columns_where(line_through(triangle.hull[i], triangle.hull[(i + 1) % n]), row_box, one, false));
  if (touch.first > touch.last) return spans;
  spans.touch_first = int64_t(touch.first);
  spans.touch_last = int64_t(touch.last);
  if (triangle.area_sign == 0) return spans;
  Span full = touch;
  for (const auto& variants : triangle.edge)
    for (const LineEquation& variant : variants) narrow(full, columns_where(variant, row_box, one, true));
  if (full.first <= full.last) {
    spans.full_first = int64_t(full.first);
    spans.full_last = int64_t(full.last);
  }
  return spans;
}

}  // namespace rastercmp::cpu::spec
