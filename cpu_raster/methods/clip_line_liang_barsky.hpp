// Liang–Barsky clipping of a 2D segment against an axis-aligned window (y up), in one pass.
// Notes: lecture-rasterization-depth-sorting-culling.txt "Liang-Barsky Clipping" (p(a) =
// (1 - a) p1 + a p2, the ordering of the four crossing parameters) and "Advantages" (no re-runs).
//
// Does: for each side k (left, right, bottom, top) the crossing parameter t = q_k / p_k of the
//       line, entering (p_k < 0) raising t_in and leaving (p_k > 0) lowering t_out, stopping as
//       soon as t_in > t_out; reports t_in / t_out and the visible segment.
// Does not: clip against non-rectangular windows (clip_line_cyrus_beck.hpp is the general form)
//       or in 3D (clip_line_cohen_sutherland_3d.hpp).
#pragma once

#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

struct LiangBarskyResult {
  bool accepted = false;
  double t_in = 0;         // parameter of the visible part's first point along p0 -> p1
  double t_out = 1;        // parameter of its last point
  Segment2 segment;        // p(t_in), p(t_out); meaningful only when accepted
  int sides_examined = 0;  // 4 unless rejected early; there is never a second pass
};

LiangBarskyResult clip_line_liang_barsky(Segment2 segment, const Rect2& window);

}  // namespace rastercmp::methods
