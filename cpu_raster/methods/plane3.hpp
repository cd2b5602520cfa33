// Planar convex polygons in 3D and their planes: the shared ground of the visibility methods
// (painter's algorithm, BSP tree, back-face culling, z-buffer).
//
// Does: Newell's normal of a polygon (right-handed: counter-clockwise seen from the side the
//       normal points to), the plane n.p + d = 0, signed distance, splitting a convex polygon by a
//       plane into its front (n.p + d > 0) and back parts, and the side of a homogeneous viewer
//       (w = 1: a point; w = 0: a direction towards a viewer at infinity).
// Does not: check planarity or convexity of the input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

struct Polygon3 {
  std::vector<Vec3> vertices;
  uint32_t id = 0;  // who owns the pixels it covers; split pieces keep it
};

struct Plane3 {
  Vec3 normal;  // not normalised
  double d = 0;
};

// Newell's method; a zero normal for a polygon with no area.
Vec3 newell_normal(const std::vector<Vec3>& vertices);

// Throws std::invalid_argument for a polygon with no area.
Plane3 plane_of(const Polygon3& polygon);

inline double signed_distance(const Plane3& plane, Vec3 p) { return dot(plane.normal, p) + plane.d; }

// > 0 in front of the plane, < 0 behind, 0 on it; for a direction (w = 0) the sign of n.v.
double viewer_side(const Plane3& plane, Vec4 viewer);

enum class PlaneSide { Front, Back, Coplanar, Spanning };

// Vertices within `epsilon` (distance in units of |normal|) count as on the plane.
PlaneSide classify(const Polygon3& polygon, const Plane3& plane, double epsilon);

struct SplitPolygon {
  Polygon3 front, back;  // either may be empty (no vertices)
};

// Sutherland–Hodgman against the plane, once per side; on-plane vertices go to both parts.
SplitPolygon split(const Polygon3& polygon, const Plane3& plane, double epsilon);

}  // namespace rastercmp::methods
