// Plain points, segments, windows and polygons (double precision) shared by the classic methods
// of docs/methods.md. The methods are space-agnostic: a caller names its values by the space it
// passes in (pos_window, pos_clip, pos_view).
//
// Does: value types, the few vector operations the methods need, shoelace area, convexity test,
//       point-in-polygon by crossing parity and by winding number.
// Does not: robust (exact) predicates — every test is an ordinary double computation.
#pragma once

#include <cstddef>
#include <vector>

namespace rastercmp::methods {

struct Vec2 {
  double x = 0, y = 0;
  friend bool operator==(const Vec2&, const Vec2&) = default;
};
struct Vec3 {
  double x = 0, y = 0, z = 0;
  friend bool operator==(const Vec3&, const Vec3&) = default;
};
// Homogeneous point (clip space) or, with w = 0, a direction.
struct Vec4 {
  double x = 0, y = 0, z = 0, w = 0;
  friend bool operator==(const Vec4&, const Vec4&) = default;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// z component of the 3D cross product: > 0 when b turns counter-clockwise from a (y up).
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// The notes' parametric form p(t) = (1 - t) p0 + t p1 (rasterization lecture, "Liang-Barsky
// Clipping"): exact at t = 0 and t = 1.
inline Vec2 lerp(Vec2 p0, Vec2 p1, double t) { return {(1 - t) * p0.x + t * p1.x, (1 - t) * p0.y + t * p1.y}; }
inline Vec3 lerp(Vec3 p0, Vec3 p1, double t) {
  return {(1 - t) * p0.x + t * p1.x, (1 - t) * p0.y + t * p1.y, (1 - t) * p0.z + t * p1.z};
}
inline Vec4 lerp(Vec4 p0, Vec4 p1, double t) {
  return {(1 - t) * p0.x + t * p1.x, (1 - t) * p0.y + t * p1.y, (1 - t) * p0.z + t * p1.z, (1 - t) * p0.w + t * p1.w};
}

struct Segment2 {
  Vec2 p0, p1;
};

// Closed axis-aligned window: x_min <= x <= x_max, y_min <= y <= y_max (y up, as in the notes).
struct Rect2 {
  double x_min = 0, y_min = 0, x_max = 0, y_max = 0;
};
// Closed axis-aligned box.
struct Box3 {
  double x_min = 0, y_min = 0, z_min = 0, x_max = 0, y_max = 0, z_max = 0;
};

// A polygon as its vertex loop (the closing edge back to the first vertex is implied).
using Polygon2 = std::vector<Vec2>;

// Shoelace area: > 0 for counter-clockwise vertices in y-up coordinates.
double signed_area(const Polygon2& polygon);

// Convex with non-zero area; collinear vertices are allowed.
bool is_convex(const Polygon2& polygon);

// The window as a counter-clockwise polygon (x_min,y_min), (x_max,y_min), (x_max,y_max), (x_min,y_max).
Polygon2 rect_polygon(const Rect2& window);

// Winding number of `polygon` around `p` (counter-clockwise turns count +1). Edges are half-open
// in y (lower end included, upper end excluded), so a point exactly on an edge gets a defined,
// but arbitrary, answer.
int winding_number(const Polygon2& polygon, Vec2 p);

// Odd-even parity rule: a ray from p to +x crosses an odd number of edges (same half-open edges).
bool inside_even_odd(const Polygon2& polygon, Vec2 p);

}  // namespace rastercmp::methods
