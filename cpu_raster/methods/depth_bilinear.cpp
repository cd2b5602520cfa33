#include "cpu_raster/methods/depth_bilinear.hpp"

#include <algorithm>
#include <utility>

namespace rastercmp::methods {

double lerp_edge_at_y(Vec3 q1, Vec3 q2, double y) {
  const double dy = q2.y - q1.y;
  return (y - q1.y) / dy * q2.z + (q2.y - y) / dy * q1.z;
}

double edge_x_at_y(Vec3 q1, Vec3 q2, double y) {
  const double dy = q2.y - q1.y;
  return (y - q1.y) / dy * q2.x + (q2.y - y) / dy * q1.x;
}

double lerp_span_at_x(Vec3 r1, Vec3 r2, double x) {
  const double dx = r2.x - r1.x;
  return (x - r1.x) / dx * r2.z + (r2.x - x) / dx * r1.z;
}

std::optional<double> bilinear_depth_in_triangle(const std::array<Vec3, 3>& triangle, Vec2 p) {
  std::array<Vec3, 3> v = triangle;
  std::sort(v.begin(), v.end(), [](const Vec3& a, const Vec3& b) { return a.y < b.y; });
  if (v[0].y == v[2].y || p.y < v[0].y || p.y > v[2].y) return std::nullopt;
  // The long edge v0 -> v2 spans every scanline; the short one is v0 -> v1 below v1 and v1 -> v2
  // above it. A horizontal short edge is never chosen: p.y on it picks the other short edge.
  const bool lower = p.y < v[1].y || v[1].y == v[2].y;
  const Vec3 short_a = lower ? v[0] : v[1], short_b = lower ? v[1] : v[2];
  Vec3 r1{edge_x_at_y(v[0], v[2], p.y), p.y, lerp_edge_at_y(v[0], v[2], p.y)};
  Vec3 r2{edge_x_at_y(short_a, short_b, p.y), p.y, lerp_edge_at_y(short_a, short_b, p.y)};
  if (r1.x > r2.x) std::swap(r1, r2);
  if (p.x < r1.x || p.x > r2.x) return std::nullopt;
  if (r1.x == r2.x) return r1.z;  // a vertex: the span is a point
  return lerp_span_at_x(r1, r2, p.x);
}

}  // namespace rastercmp::methods
