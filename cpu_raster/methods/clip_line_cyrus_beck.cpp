#include "cpu_raster/methods/clip_line_cyrus_beck.hpp"

#include <algorithm>
#include <stdexcept>

namespace rastercmp::methods {

namespace {

// Outward normal of edge a -> b of a polygon with the given orientation sign (+1: ccw, y up).
Vec2 outward_normal(Vec2 a, Vec2 b, double orientation) {
  const Vec2 e = b - a;
  return orientation > 0 ? Vec2{e.y, -e.x} : Vec2{-e.y, e.x};
}

CyrusBeckResult clip_point(Vec2 p, const Polygon2& window, double orientation) {
  CyrusBeckResult result;
  for (size_t i = 0; i < window.size(); ++i) {
    const Vec2 n = outward_normal(window[i], window[(i + 1) % window.size()], orientation);
    if (dot(n, p - window[i]) > 0) return result;  // outside this edge's half-plane
  }
  result.accepted = true;
  result.segment = {p, p};
  return result;
}

}  // namespace

CyrusBeckResult clip_line_cyrus_beck(Segment2 segment, const Polygon2& convex_window) {
  if (!is_convex(convex_window)) {
    throw std::invalid_argument("clip_line_cyrus_beck: the window must be a convex polygon with non-zero area");
  }
  const double orientation = signed_area(convex_window) > 0 ? 1 : -1;
  const Vec2 p0 = segment.p0, d = segment.p1 - segment.p0;
  if (d.x == 0 && d.y == 0) return clip_point(p0, convex_window, orientation);

  CyrusBeckResult result;
  bool outside_parallel = false;
  for (size_t i = 0; i < convex_window.size(); ++i) {
    const Vec2 p_edge = convex_window[i];
    const Vec2 n = outward_normal(p_edge, convex_window[(i + 1) % convex_window.size()], orientation);
    const double n_dot_d = dot(n, d);
    CyrusBeckStep step{i, CyrusBeckCrossing::Parallel, 0, result.t_in, result.t_out};
    if (n_dot_d == 0) {
      outside_parallel = outside_parallel || dot(n, p0 - p_edge) > 0;
    } else {
      step.t_hit = dot(n, p0 - p_edge) / -n_dot_d;  // t = N.(p0 - pE) / (-N.D)
      if (n_dot_d < 0) {                            // potentially entering
        step.crossing = CyrusBeckCrossing::Entering;
        result.t_in = std::max(result.t_in, step.t_hit);
      } else {  // potentially leaving
        step.crossing = CyrusBeckCrossing::Leaving;
        result.t_out = std::min(result.t_out, step.t_hit);
      }
      step.t_in = result.t_in;
      step.t_out = result.t_out;
    }
    result.trace.push_back(step);
  }
  if (outside_parallel || result.t_in > result.t_out) return result;
  result.accepted = true;
  result.segment = {lerp(segment.p0, segment.p1, result.t_in), lerp(segment.p0, segment.p1, result.t_out)};
  return result;
}

}  // namespace rastercmp::methods
