// Bresenham's integer line algorithm, the notes' "Complete Bresenham's line drawing algorithm"
// (lecture-rasterization-depth-sorting-culling.txt):
//
//   steep := |y1 - y0| > |x1 - x0|;  if steep: swap(x0, y0), swap(x1, y1)
//   if x0 > x1: swap(x0, x1), swap(y0, y1)
//   deltax := x1 - x0; deltay := |y1 - y0|; error := 0; ystep := y0 < y1 ? 1 : -1; y := y0
//   for x from x0 to x1: plot (steep ? (y, x) : (x, y)); error += deltay;
//                        if 2 * error >= deltax: y += ystep; error -= deltax
//
// Does: all octants with integers only. Because of the x0 > x1 swap the pixels come in
//       increasing major-axis order, which is p1 -> p0 for lines drawn "backwards". An exact
//       half (2 * error == deltax) steps the minor axis, towards y1 after the swap.
// Does not: keep p0 -> p1 order, make a line and its reverse always hit the same pixels (the
//       half-way rule depends on the direction after the swap), anti-alias, or clip.
#pragma once

#include <vector>

#include "cpu_raster/methods/spans.hpp"

namespace rastercmp::methods {

std::vector<PixelXY> line_bresenham(PixelXY p0, PixelXY p1);

// The decision variables of line_bresenham, step by step (in its pixel order): the error term
// after `error += deltay`, whether 2 * error >= deltax stepped the minor axis, and the error after.
struct BresenhamStep {
  PixelXY pixel;
  int64_t error_added = 0;  // error + deltay, compared as 2 * error_added >= delta_x
  bool minor_step = false;  // the minor axis stepped after this pixel
  int64_t error_after = 0;  // error_added, less delta_x when it stepped
};
struct BresenhamTrace {
  bool steep = false;    // x and y swapped
  bool swapped = false;  // the endpoints swapped (x0 > x1 after the steep swap): pixels run p1 -> p0
  int64_t delta_x = 0, delta_y = 0, y_step = 1;  // after the swaps
  std::vector<BresenhamStep> steps;
};
BresenhamTrace line_bresenham_trace(PixelXY p0, PixelXY p1);

}  // namespace rastercmp::methods
