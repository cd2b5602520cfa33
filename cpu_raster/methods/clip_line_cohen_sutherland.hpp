// Cohen–Sutherland clipping of a 2D segment against an axis-aligned window (y up).
// Notes: notes-line-clipping-hidden-surface.txt "Line Clipping" (outcode Y0Y1X0X1);
// lecture-depth-clipping-polygon-offset.txt "Cohen-Sutherland" (Outcode, ClipOnce, Clip Loop);
// lecture-rasterization-depth-sorting-culling.txt "Cohen-Sutherland Algorithm".
//
// Does: 4-bit outcodes in either of the notes' bit layouts, trivial accept (OR == 0) and reject
//       (AND != 0), then one ClipOnce per pass: the outside endpoint (the first one if both are
//       outside) is replaced by the intersection with one window side whose bit it has set,
//       chosen in a fixed side order. Counts passes and intersections.
// Does not: clip against anything but a rectangle (see clip_line_cyrus_beck.hpp), promise the
//       same rounding as the parametric clippers (they agree within a few ulps), or keep the
//       segment's direction information beyond p0 -> p1.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

enum class RectSide { XMin, XMax, YMin, YMax };  // left, right, bottom, top (y up)

enum class OutcodeLayout {
  // notes-line-clipping-hidden-surface.txt Y0Y1X0X1 (= Angel's b0b1b2b3, the fill lecture's
  // "A = 0001 left, B = 0100 bottom"): 8 y > y_max, 4 y < y_min, 2 x > x_max, 1 x < x_min.
  Notes,
  // lecture-depth-clipping-polygon-offset.txt Outcode(): 8 x < left, 4 y > top, 2 x > right,
  // 1 y < bottom.
  Comp342,
};

uint8_t outcode_bit(RectSide side, OutcodeLayout layout);

// The outcode of a point: one bit per window side the point lies strictly outside of.
uint8_t outcode(Vec2 p, const Rect2& window, OutcodeLayout layout = OutcodeLayout::Notes);

struct CohenSutherlandOptions {
  OutcodeLayout layout = OutcodeLayout::Notes;
  // Which set bit of the outside endpoint is clipped first ("Pick one & replace endpoint with
  // intersection"). The default is Foley & van Dam's top, bottom, right, left.
  std::array<RectSide, 4> side_order{RectSide::YMax, RectSide::YMin, RectSide::XMax, RectSide::XMin};
};

// One ClipOnce: the outcodes of the current endpoints and what the pass did with them.
struct CohenSutherlandPass {
  uint8_t code_p0 = 0, code_p1 = 0;
  bool clipped = false;            // false: this pass accepted (OR == 0) or rejected (AND != 0)
  bool clipped_p0 = false;         // the p0 end was replaced (else p1)
  RectSide side = RectSide::XMin;  // the side it was cut at, when clipped
};

struct CohenSutherlandResult {
  bool accepted = false;
  Segment2 segment;  // the visible part, p0 side first; meaningful only when accepted
  int passes = 0;    // ClipOnce calls (outcode evaluations of the pair), including the final accept/reject
  int clips = 0;     // endpoint replacements (intersections computed)
  std::vector<CohenSutherlandPass> trace;  // one row per pass
};

// Passes are bounded: a segment that grazes a window corner can make rounding alternate between
// two sides; after kCohenSutherlandMaxPasses it is rejected (its visible part is a point).
inline constexpr int kCohenSutherlandMaxPasses = 16;

CohenSutherlandResult clip_line_cohen_sutherland(Segment2 segment, const Rect2& window,
                                                 const CohenSutherlandOptions& options = {});

}  // namespace rastercmp::methods
