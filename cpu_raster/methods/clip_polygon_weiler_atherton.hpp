// Weiler–Atherton clipping: the intersection of a subject polygon with a clip polygon, both
// simple and possibly concave; the result may be several polygons.
// Notes: lecture-depth-clipping-polygon-offset.txt "Clipping algorithms" ("Weiler-Atherton
// (poly vs poly)"); lecture-rasterization-depth-sorting-culling.txt "Polygon Clipping" ("Clipping
// a polygon can yield multiple polygons").
//
// Does: makes both loops counter-clockwise, inserts every proper edge crossing into both vertex
//       lists (sorted along each edge), marks each crossing entering or leaving the clip region,
//       then from each unvisited entering crossing follows the subject list to the next crossing,
//       switches to the clip list, and so on back to the start. Without crossings the result is
//       the subject (inside the clip), the clip (inside the subject) or nothing. Output loops are
//       counter-clockwise.
// Does not: handle degenerate contact — a vertex on the other polygon's boundary, or overlapping
//       collinear edges. Those are detected (with ordinary double predicates) and reported as
//       `degenerate` with no polygons; perturb the input to get an answer. Does not compute union
//       or difference, nor accept self-intersecting loops or polygons with holes.
#pragma once

#include <cstddef>
#include <vector>

#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

struct WeilerAthertonResult {
  std::vector<Polygon2> polygons;  // the pieces of subject ∩ clip
  bool degenerate = false;         // degenerate contact found; `polygons` is empty
  size_t crossings = 0;            // proper edge crossings found
};

// Throws std::invalid_argument if either polygon has fewer than 3 vertices or zero area.
WeilerAthertonResult clip_polygon_weiler_atherton(const Polygon2& subject, const Polygon2& clip);

}  // namespace rastercmp::methods
