#include "cpu_raster/methods/geometry.hpp"

#include <cmath>
#include <cstddef>

namespace rastercmp::methods {

double signed_area(const Polygon2& polygon) {
  double twice_area = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 a = polygon[i];
    const Vec2 b = polygon[(i + 1) % polygon.size()];
    twice_area += cross(a, b);
  }
  return twice_area / 2;
}

bool is_convex(const Polygon2& polygon) {
  if (polygon.size() < 3 || signed_area(polygon) == 0) return false;
  // Every turn the same way and the edge direction turning exactly once in total: a pentagram
  // turns the same way at every vertex but twice around.
  bool seen_left = false, seen_right = false;
  double total_turn = 0;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = polygon[i], b = polygon[(i + 1) % n], c = polygon[(i + 2) % n];
    const Vec2 in = b - a, out = c - b;
    const double turn = cross(in, out);
    if (turn == 0 && dot(in, out) < 0) return false;  // the boundary doubles back
    seen_left = seen_left || turn > 0;
    seen_right = seen_right || turn < 0;
    total_turn += std::atan2(turn, dot(in, out));
  }
  constexpr double kTwoPi = 6.283185307179586;
  return !(seen_left && seen_right) && std::fabs(std::fabs(total_turn) - kTwoPi) < 1e-6;
}

Polygon2 rect_polygon(const Rect2& window) {
  return {{window.x_min, window.y_min},
          {window.x_max, window.y_min},
          {window.x_max, window.y_max},
          {window.x_min, window.y_max}};
}

int winding_number(const Polygon2& polygon, Vec2 p) {
  int winding = 0;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = polygon[i], b = polygon[(i + 1) % n];
    const double side = cross(b - a, p - a);  // > 0: p left of a->b
    if (a.y <= p.y && p.y < b.y && side > 0)
      ++winding;  // upward edge, p on its left
    else if (b.y <= p.y && p.y < a.y && side < 0)
      --winding;  // downward edge, p on its right
  }
  return winding;
}

bool inside_even_odd(const Polygon2& polygon, Vec2 p) {
  bool inside = false;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = polygon[i], b = polygon[(i + 1) % n];
    const bool spans = (a.y <= p.y && p.y < b.y) || (b.y <= p.y && p.y < a.y);
    if (!spans) continue;
    const Vec2 lo = a.y < b.y ? a : b, hi = a.y < b.y ? b : a;
    const double x_cross = lo.x + (p.y - lo.y) * (hi.x - lo.x) / (hi.y - lo.y);
    if (x_cross > p.x) inside = !inside;
  }
  return inside;
}

}  // namespace rastercmp::methods
