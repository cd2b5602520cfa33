#include "cpu_raster/methods/clip_polygon_sutherland_hodgman.hpp"

#include <stdexcept>

namespace rastercmp::methods {

namespace {

// One boundary pass over the subject loop; `distance(p)` >= 0 inside, `cross(s, e)` the crossing.
template <typename Point, typename Distance, typename Crossing>
std::vector<Point> clip_against_boundary(const std::vector<Point>& subject, Distance distance, Crossing crossing) {
  std::vector<Point> out;
  if (subject.empty()) return out;
  Point s = subject.back();
  bool s_in = distance(s) >= 0;
  for (const Point& e : subject) {
    const bool e_in = distance(e) >= 0;
    if (s_in && e_in) {
      out.push_back(e);
    } else if (s_in && !e_in) {
      out.push_back(crossing(s, e));
    } else if (!s_in && e_in) {
      out.push_back(crossing(s, e));
      out.push_back(e);
    }
    s = e;
    s_in = e_in;
  }
  return out;
}

}  // namespace

Polygon2 clip_polygon_sutherland_hodgman(const Polygon2& subject, const Polygon2& convex_window) {
  if (!is_convex(convex_window)) {
    throw std::invalid_argument("clip_polygon_sutherland_hodgman: the window must be convex with non-zero area");
  }
  const double orientation = signed_area(convex_window) > 0 ? 1 : -1;
  Polygon2 polygon = subject;
  for (size_t i = 0; i < convex_window.size() && !polygon.empty(); ++i) {
    const Vec2 a = convex_window[i], b = convex_window[(i + 1) % convex_window.size()];
    // Inside = the window's side of edge a -> b (left for a counter-clockwise window).
    auto distance = [&](Vec2 p) { return orientation * cross(b - a, p - a); };
    auto crossing = [&](Vec2 s, Vec2 e) {
      const double d_s = distance(s), d_e = distance(e);
      return lerp(s, e, d_s / (d_s - d_e));
    };
    polygon = clip_against_boundary(polygon, distance, crossing);
  }
  return polygon;
}

Polygon2 clip_polygon_sutherland_hodgman(const Polygon2& subject, const Rect2& window) {
  return clip_polygon_sutherland_hodgman(subject, rect_polygon(window));
}

std::vector<Vec4> clip_polygon_sutherland_hodgman(const std::vector<Vec4>& subject_clip, const ClipVolume& volume) {
  std::vector<Vec4> polygon = subject_clip;
  for (ClipPlane plane : kClipPlanes) {
    if (polygon.empty()) break;
    auto distance = [&](Vec4 p) { return plane_distance(volume, plane, p); };
    auto crossing = [&](Vec4 s, Vec4 e) { return intersect_plane(volume, plane, s, e); };
    polygon = clip_against_boundary(polygon, distance, crossing);
  }
  return polygon;
}

}  // namespace rastercmp::methods
