// Must / may / must-not coverage of one line segment (after clipping). Vulkan "Line Segments"
// (primsrast.adoc, docs/lavapipe-rules.md §5.1) gives each mode an ideal region:
//  - RECTANGULAR (and DEFAULT on a strictLines device): the rectangle of width lineWidth centred
//    on the segment;
//  - DEFAULT without strictLines: a parallelogram whose end edges, along the minor axis, are
//    lineWidth long; the profile does not know the device's strictLines, so a DEFAULT line is Must
//    only inside both shapes and May near either;
//  - BRESENHAM: the diamond-exit fragments, a parallelogram with minor-axis extent
//    round(lineWidth) (rounded either way here), ends within half a pixel, ±1 fragment.
// As the CTS line verification is weaker than the triangle one, the profile keeps a margin of one
// pixel (plus the pixel box) both ways: Must only one pixel inside the ideal region, May up to one
// pixel outside it. May regions also reach half the line width past each end, for devices that cap
// or clip wide lines differently, and Must stays inside the viewport rectangle (only the segment
// is clipped; what a wide line covers past the viewport is the device's choice). Line coordinates
// stay in double: the margins dwarf snapping.
#pragma once

#include <array>
#include <vector>

#include <glm/vec2.hpp>

#include "cpu_raster/spec/triangle_coverage.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::spec {

inline constexpr double kLineMarginPx = 1.0;

// A convex quadrilateral in window pixels, corners in order (either winding).
struct Quad {
  std::array<glm::dvec2, 4> corner{};
};

struct LineShape {
  std::vector<Quad> must;  // Must needs the box, grown by the margin, inside every one (none: never);
                           // the caller adds the viewport rectangle
  std::vector<Quad> may;   // May where the box, grown by the margin, touches any one
};

// The widest width a device may rasterize a line of `line_width` with: the nearest supported width
// (Vulkan "Line Segments"), lineWidthGranularity unknown (at most 1.0, "Limit Requirements").
double widest_line_width(float line_width);

// pos_window: the clipped endpoints in window pixels (finite). Must from the narrowest width a
// device may use for `line_width`, May from the widest.
LineShape line_shape(const std::array<glm::dvec2, 2>& pos_window, LineMode mode, float line_width);

// The box of pixel (px, py) in pixels: centre and half-size (see pixel_box).
struct PixelSquare {
  glm::dvec2 centre{0, 0};
  double half = 0;
};

Coverage classify_line_box(const LineShape& shape, const PixelSquare& box);

// Bounds of everything the May quads (plus margin) can reach, in pixels.
struct PixelBounds {
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;
};
PixelBounds may_bounds(const LineShape& shape);

// The x extent of the May quads within the horizontal band [y_lo, y_hi] (margin not included);
// empty (x_min > x_max) when they miss it. Every box that classify_line_box does not call NONE and
// whose grown square lies in the band overlaps this extent grown by the margin.
struct XExtent {
  double x_min = 1, x_max = 0;
};
XExtent may_extent_in_band(const LineShape& shape, double y_lo, double y_hi);

// Where classify_line_box may answer other than NONE for boxes of half-size `half_px`: the rows
// within [lo, hi], and per row the columns within [lo, hi] (from may_bounds and
// may_extent_in_band). Empty spans have last < first.
struct IndexSpan {
  int32_t first = 0, last = -1;
};
IndexSpan line_rows(const LineShape& shape, double half_px, int32_t lo, int32_t hi);
IndexSpan line_columns(const LineShape& shape, double half_px, int32_t py, int32_t lo, int32_t hi);

}  // namespace rastercmp::cpu::spec
