// The lecture's scanline polygon fill, exactly as lecture-clipping-fill-zbuffer.txt defines it
// ("Polygon Filling - Approach", "Details of Polygon Filling", "Boundary Top & Bottoms",
// "Pseudo-Code"):
//
//   for (y = Ymin; y < Ymax; y++) {
//     ignore horizontal boundaries; intersect scanline with boundaries; ignore top vertex;
//     sort intersections by increasing x;
//     for every pair of intersections: for (x = ceil(first); x < ceil(last); x++) fill(x, y);
//   }
//
// Conventions, all the notes': pixel (x, y) is the integer point (x, y) (the notes' vertices and
// intersections are in pixel units, with no half-pixel offset); y grows upward as in the notes'
// figures but nothing depends on it; an edge is closed at its bottom and open at its top
// (y_low <= y < y_high); pairs are (1st, 2nd), (3rd, 4th), ... — the odd-even parity rule. A
// vertex where two edges start (the notes' "(3,0) (3,0)" case) gives an empty pair and is not
// filled, as the pseudo-code does (the notes: "Today's answer: Maybe").
//
// Does: any polygon, including concave and self-intersecting ones (parity). Shifting a polygon by
//       (-0.5, -0.5) makes it sample at pixel centres (x + 0.5, y + 0.5).
// Does not: non-zero winding (fill_polygon_rule.hpp), anti-aliasing, depth.
#pragma once

#include <vector>

#include "cpu_raster/methods/geometry.hpp"
#include "cpu_raster/methods/spans.hpp"

namespace rastercmp::methods {

// The x of every crossing of scanline y with a non-horizontal edge, edges closed at the bottom
// and open at the top, sorted increasing. Each x is computed from the edge's lower end, so an
// edge shared by two polygons gives both the same bits.
std::vector<double> scanline_intersections_notes(const Polygon2& polygon, double y);

// Spans for y = ceil(y_min) .. y < y_max of the polygon, clamped to `bounds`.
std::vector<Span> fill_scanline_notes(const Polygon2& polygon, const PixelBounds& bounds = {});

}  // namespace rastercmp::methods
