#include "cpu_raster/methods/plane3.hpp"

#include <cmath>
#include <stdexcept>

namespace rastercmp::methods {

Vec3 newell_normal(const std::vector<Vec3>& vertices) {
  Vec3 n;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const Vec3 a = vertices[i], b = vertices[(i + 1) % vertices.size()];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

Plane3 plane_of(const Polygon3& polygon) {
  const Vec3 n = newell_normal(polygon.vertices);
  if (n.x == 0 && n.y == 0 && n.z == 0) throw std::invalid_argument("plane_of: polygon has no area");
  Vec3 centroid;
  for (const Vec3& v : polygon.vertices) centroid = centroid + v;
  centroid = centroid * (1.0 / double(polygon.vertices.size()));
  return {n, -dot(n, centroid)};
}

double viewer_side(const Plane3& plane, Vec4 viewer) {
  return dot(plane.normal, Vec3{viewer.x, viewer.y, viewer.z}) + plane.d * viewer.w;
}

namespace {

double scaled_distance(const Plane3& plane, Vec3 p) {
  return signed_distance(plane, p) / std::sqrt(dot(plane.normal, plane.normal));
}

}  // namespace

PlaneSide classify(const Polygon3& polygon, const Plane3& plane, double epsilon) {
  bool front = false, back = false;
  for (const Vec3& v : polygon.vertices) {
    const double dist = scaled_distance(plane, v);
    front = front || dist > epsilon;
    back = back || dist < -epsilon;
  }
  if (front && back) return PlaneSide::Spanning;
  if (front) return PlaneSide::Front;
  if (back) return PlaneSide::Back;
  return PlaneSide::Coplanar;
}

SplitPolygon split(const Polygon3& polygon, const Plane3& plane, double epsilon) {
  SplitPolygon out{{{}, polygon.id}, {{}, polygon.id}};
  const std::vector<Vec3>& v = polygon.vertices;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 s = v[i], e = v[(i + 1) % v.size()];
    const double ds = scaled_distance(plane, s), de = scaled_distance(plane, e);
    const int side_s = ds > epsilon ? 1 : (ds < -epsilon ? -1 : 0);
    const int side_e = de > epsilon ? 1 : (de < -epsilon ? -1 : 0);
    if (side_s >= 0) out.front.vertices.push_back(s);
    if (side_s <= 0) out.back.vertices.push_back(s);
    if (side_s * side_e < 0) {  // the edge crosses the plane
      const Vec3 crossing = lerp(s, e, ds / (ds - de));
      out.front.vertices.push_back(crossing);
      out.back.vertices.push_back(crossing);
    }
  }
  if (out.front.vertices.size() < 3) out.front.vertices.clear();
  if (out.back.vertices.size() < 3) out.back.vertices.clear();
  return out;
}

}  // namespace rastercmp::methods
