// Cyrus–Beck clipping of a 2D segment against any convex polygon window.
// Notes: lecture-graphics-pipeline-cyrus-beck.txt "Cyrus-Beck Algorithm" (t = N.(p0 - pE) /
// (-N.D), N.D < 0 potentially entering, > 0 potentially leaving, t_E = max, t_L = min);
// lecture-depth-clipping-polygon-offset.txt "Cyrus Beck" (the t_in / t_out table).
//
// Does: outward edge normals from the window's orientation (either orientation is accepted),
//       one trace row per window edge in vertex order (the notes' table without its first row
//       t_in = 0, t_out = 1), the visible segment. A segment parallel to an edge and outside it
//       is rejected (the notes' pseudocode only skips parallel edges; that would accept it).
//       A degenerate segment (p0 == p1) is clipped as a point, as the notes say.
// Does not: accept non-convex windows (throws std::invalid_argument; see
//       clip_polygon_weiler_atherton.hpp for concave regions).
#pragma once

#include <cstddef>
#include <vector>

#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

enum class CyrusBeckCrossing { Entering, Leaving, Parallel };

struct CyrusBeckStep {
  size_t edge = 0;  // window edge i runs from vertex i to vertex i+1
  CyrusBeckCrossing crossing = CyrusBeckCrossing::Parallel;
  double t_hit = 0;  // of the line with the edge's line; 0 for a parallel edge
  double t_in = 0;   // after this edge
  double t_out = 1;  // after this edge
};

struct CyrusBeckResult {
  bool accepted = false;
  double t_in = 0, t_out = 1;
  Segment2 segment;                  // p(t_in), p(t_out); meaningful only when accepted
  std::vector<CyrusBeckStep> trace;  // empty for a degenerate segment
};

// `convex_window`: at least 3 vertices, convex, non-zero area; throws std::invalid_argument if not.
CyrusBeckResult clip_line_cyrus_beck(Segment2 segment, const Polygon2& convex_window);

}  // namespace rastercmp::methods
