// DDA (digital differential analyzer) line scan conversion between integer endpoints.
// Notes: lecture-rasterization-depth-sorting-culling.txt "DDA Algorithm" (y = y1; for x = x1 ..
// x2: write_pixel(x, round(y)); y += k) and "Using Symmetry" (for |k| > 1 swap the roles of x
// and y).
//
// Does: all octants. Steps one pixel along the major axis from p0 towards p1 (both included) and
//       accumulates the minor coordinate in double by repeated addition of the slope, as the notes
//       do; round(v) is floor(v + 0.5) (halves go towards +infinity). Pixels come in p0 -> p1 order.
// Does not: avoid the accumulated rounding error of the repeated addition (exactly what
//       line_bresenham.hpp's integer error term avoids), anti-alias, or clip.
#pragma once

#include <vector>

#include "cpu_raster/methods/spans.hpp"

namespace rastercmp::methods {

std::vector<PixelXY> line_dda(PixelXY p0, PixelXY p1);

// The decision variables of line_dda, step by step: the accumulated minor coordinate before
// rounding (the x of a steep line, else the y) and the pixel it rounds to.
struct DdaStep {
  PixelXY pixel;
  double minor = 0;  // accumulated by repeated addition of the slope; pixel = floor(minor + 0.5)
};
struct DdaTrace {
  bool steep = false;          // |dy| > |dx|: steps along y, x is the minor axis
  int32_t major_step = 1;      // +1 or -1 per step along the major axis
  double slope = 0;            // minor change per major step
  std::vector<DdaStep> steps;  // p0 -> p1, the pixels of line_dda
};
DdaTrace line_dda_trace(PixelXY p0, PixelXY p1);

}  // namespace rastercmp::methods
