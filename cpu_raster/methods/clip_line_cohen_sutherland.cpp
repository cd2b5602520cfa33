#include "cpu_raster/methods/clip_line_cohen_sutherland.hpp"

namespace rastercmp::methods {

uint8_t outcode_bit(RectSide side, OutcodeLayout layout) {
  if (layout == OutcodeLayout::Notes) {  // Y0Y1X0X1
    switch (side) {
      case RectSide::YMax: return 8;
      case RectSide::YMin: return 4;
      case RectSide::XMax: return 2;
      case RectSide::XMin: return 1;
    }
  }
  switch (side) {  // COMP342 Outcode(): left 8, top 4, right 2, bottom 1
    case RectSide::XMin: return 8;
    case RectSide::YMax: return 4;
    case RectSide::XMax: return 2;
    case RectSide::YMin: return 1;
  }
  return 0;
}

uint8_t outcode(Vec2 p, const Rect2& window, OutcodeLayout layout) {
  uint8_t code = 0;
  if (p.x < window.x_min) code |= outcode_bit(RectSide::XMin, layout);
  if (p.y > window.y_max) code |= outcode_bit(RectSide::YMax, layout);
  if (p.x > window.x_max) code |= outcode_bit(RectSide::XMax, layout);
  if (p.y < window.y_min) code |= outcode_bit(RectSide::YMin, layout);
  return code;
}

namespace {

// The point of the line p -> q on a window side, by similar triangles ("Clipping a point"). The
// clipped coordinate is set exactly to the side, so that side's bit is clear afterwards.
Vec2 intersect_side(Vec2 p, Vec2 q, RectSide side, const Rect2& window) {
  switch (side) {
    case RectSide::XMin:
    case RectSide::XMax: {
      const double x = side == RectSide::XMin ? window.x_min : window.x_max;
      return {x, p.y + (q.y - p.y) * (x - p.x) / (q.x - p.x)};
    }
    case RectSide::YMin:
    case RectSide::YMax: {
      const double y = side == RectSide::YMin ? window.y_min : window.y_max;
      return {p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y), y};
    }
  }
  return p;
}

RectSide first_set_side(uint8_t code, const CohenSutherlandOptions& options) {
  for (RectSide side : options.side_order) {
    if (code & outcode_bit(side, options.layout)) return side;
  }
  return options.side_order[0];  // unreachable for a non-zero code
}

}  // namespace

CohenSutherlandResult clip_line_cohen_sutherland(Segment2 segment, const Rect2& window,
                                                 const CohenSutherlandOptions& options) {
  CohenSutherlandResult result;
  Vec2 p = segment.p0, q = segment.p1;
  while (result.passes < kCohenSutherlandMaxPasses) {  // Clip Loop
    ++result.passes;                                   // ClipOnce
    const uint8_t code_p = outcode(p, window, options.layout);
    const uint8_t code_q = outcode(q, window, options.layout);
    CohenSutherlandPass& pass = result.trace.emplace_back();
    pass.code_p0 = code_p, pass.code_p1 = code_q;
    if ((code_p | code_q) == 0) {  // trivial accept
      result.accepted = true;
      result.segment = {p, q};
      return result;
    }
    if ((code_p & code_q) != 0) return result;  // trivial reject
    ++result.clips;
    pass.clipped = true;
    pass.clipped_p0 = code_p != 0;
    pass.side = first_set_side(code_p != 0 ? code_p : code_q, options);
    if (code_p != 0) {  // p is outside, clip it
      p = intersect_side(p, q, pass.side, window);
    } else {  // q is outside, clip it
      q = intersect_side(q, p, pass.side, window);
    }
  }
  return result;
}

}  // namespace rastercmp::methods
