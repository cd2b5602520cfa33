#include "cpu_raster/methods/clip_line_liang_barsky.hpp"

#include <algorithm>
#include <array>

namespace rastercmp::methods {

LiangBarskyResult clip_line_liang_barsky(Segment2 segment, const Rect2& window) {
  LiangBarskyResult result;
  const Vec2 p0 = segment.p0, d = segment.p1 - segment.p0;
  // p_k t <= q_k for the inside of side k: left, right, bottom, top.
  const std::array<double, 4> p{-d.x, d.x, -d.y, d.y};
  const std::array<double, 4> q{p0.x - window.x_min, window.x_max - p0.x, p0.y - window.y_min, window.y_max - p0.y};
  for (size_t k = 0; k < 4; ++k) {
    ++result.sides_examined;
    if (p[k] == 0) {  // parallel to side k: inside or out for the whole line
      if (q[k] < 0) return result;
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0)
      result.t_in = std::max(result.t_in, t);  // entering
    else
      result.t_out = std::min(result.t_out, t);  // leaving
    if (result.t_in > result.t_out) return result;
  }
  result.accepted = true;
  result.segment = {lerp(segment.p0, segment.p1, result.t_in), lerp(segment.p0, segment.p1, result.t_out)};
  return result;
}

}  // namespace rastercmp::methods
