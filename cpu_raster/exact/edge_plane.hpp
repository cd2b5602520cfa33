// Edge functions in 24.8 fixed point (docs/lavapipe-rules.md §2.4, steps 11-13).
// For an edge from vertex a to vertex b of a polygon made counter-clockwise (llvmpipe's sense:
// positive doubled area), dcdx = a.y - b.y, dcdy = a.x - b.x, c = dcdx*a.x - dcdy*a.y and the
// value at a sample point (Xs, Ys) is E = c + dcdy*Ys - dcdx*Xs. The fill-rule bias is decided
// here, once: inclusive (top-left) edges get c += 1, so the rasterizer only tests E > 0.
#pragma once

#include <array>
#include <cstdint>

#include "cpu_raster/exact/fixed_point.hpp"
#include "cpu_raster/exact/setup_methods.hpp"

namespace rastercmp::cpu {

struct EdgePlane {
  int64_t c = 0;           // constant, including the +1 of an inclusive edge
  int64_t dcdx = 0;        // per fixed unit of x
  int64_t dcdy = 0;        // per fixed unit of y
  bool inclusive = false;  // got the top-left +1
};

// Left edges (dcdx < 0) and the top edge (dcdx == 0, dcdy > 0) are inclusive (§2.4).
inline bool is_top_left(int64_t dcdx, int64_t dcdy) { return dcdx < 0 || (dcdx == 0 && dcdy > 0); }

inline EdgePlane make_edge(FixedPoint a, FixedPoint b, TieBreak tie_break) {
  EdgePlane edge;
  edge.dcdx = a.y.wide() - b.y.wide();
  edge.dcdy = a.x.wide() - b.x.wide();
  edge.c = edge.dcdx * a.x.wide() - edge.dcdy * a.y.wide();
  edge.inclusive = tie_break == TieBreak::TopLeft && is_top_left(edge.dcdx, edge.dcdy);
  if (edge.inclusive) edge.c += 1;
  return edge;
}

// A primitive's planes: its 3 or 4 edges, then the scissor planes set-up added (at most 8,
// lp_setup_tri.c MAX_PLANES).
struct PlaneSet {
  std::array<EdgePlane, 8> plane{};
  uint32_t count = 0;
  void push(const EdgePlane& edge) { plane[count++] = edge; }
};

inline int64_t edge_value(const EdgePlane& edge, int64_t x_fixed, int64_t y_fixed) {
  return edge.c + edge.dcdy * y_fixed - edge.dcdx * x_fixed;
}

}  // namespace rastercmp::cpu
