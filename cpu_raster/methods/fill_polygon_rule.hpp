// Scanline fill of arbitrary polygons (concave, self-intersecting) by the even-odd or the
// non-zero winding rule. Notes: lecture-rasterization-depth-sorting-culling.txt "Polygon Scan
// Conversion" (odd-even test, winding number: "inside if winding number != 0");
// lecture-clipping-fill-zbuffer.txt "Odd-even parity rule".
//
// Sampling: pixel (x, y) is covered iff its sample point (x + sample_offset, y + sample_offset)
// is inside. Edges are closed at the bottom and open at the top in y; along a row a sample
// exactly on a crossing belongs to the interval to its right. So with sample_offset = 0 and the
// even-odd rule this is exactly fill_scanline_notes.hpp, and two polygons sharing an edge never
// both cover a sample on it.
//
// Does: per row, the crossings with their direction (+1 upward, -1 downward edge), sorted by x;
//       the winding number left of each crossing decides the interval after it.
// Does not: anti-aliasing, depth; tie-breaking of coincident crossings beyond the half-open rule.
#pragma once

#include <vector>

#include "cpu_raster/methods/geometry.hpp"
#include "cpu_raster/methods/spans.hpp"

namespace rastercmp::methods {

enum class FillRule { EvenOdd, NonZero };

struct PolygonFillOptions {
  FillRule rule = FillRule::NonZero;
  double sample_offset = 0.5;  // 0.5: Vulkan/D3D pixel centres; 0: the notes' integer points
  PixelBounds bounds;
};

std::vector<Span> fill_polygon_rule(const Polygon2& polygon, const PolygonFillOptions& options);

}  // namespace rastercmp::methods
