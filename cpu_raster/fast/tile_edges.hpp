// A triangle's three edges over one rectangle of one tile, in 32-bit "G" form.
//
// The exact edge value at pixel (px, py) is E = c + 256*(dcdy*py - dcdx*px) (int64, edge_plane.hpp,
// docs/lavapipe-rules.md §2.4) and the pixel is covered iff E > 0 for every edge. With k = dcdy*py - dcdx*px
// (an integer), E > 0 <=> 256*k > -c <=> k > floor(-c/256). So G = k - floor(-c/256) is covered iff
// G > 0: the same test, with steps 256 times smaller and no fraction left over.
//
// Overflow bound for the 32-bit form. An edge that is neither all-in nor all-out over the
// rectangle takes both signs inside one 64x64 tile, so at any pixel of that tile |G| is at most
// the tile's spread 63*(|dcdx| + |dcdy|); the kernel also forms values up to 8 pixels past the
// tile (its last step, never used). With |dcdx| + |dcdy| <= kMaxEdgeStepSum = 2^24 that is
// 71 * 2^24 < 2^31. Coordinates inside the largest viewport (16384 px = 2^22 fixed units) give
// at most 2^23; the rarer larger steps (coordinates up to the set-up bound 2^25) take the scalar path.
#pragma once

#include <cstdint>
#include <limits>

#include "cpu_raster/exact/edge_plane.hpp"
#include "cpu_raster/fast/fast_triangle.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"

namespace rastercmp::cpu::fast {

inline constexpr int64_t kMaxEdgeStepSum = int64_t(1) << 24;
static_assert((kTileSize - 1 + 8) * kMaxEdgeStepSum + 1 < std::numeric_limits<int32_t>::max(),
              "32-bit edge values of a tile must not overflow");

enum class EdgeFit {
  None,    // some edge is all-out over the rectangle: nothing to draw
  Vector,  // the job's edges are set (all-in edges as constant 0 = "G - 1 >= 0")
  Scalar,  // a partial edge steps too fast for 32 bits: use the scalar kernel
};

struct EdgeSetup {
  EdgeFit fit = EdgeFit::None;
  bool all_in = false;  // every edge is all-in over the rectangle: every pixel covered
};

// Fills job.rect, job.origin_x and the edge fields for rectangle r (inside one tile).
inline EdgeSetup setup_tile_edges(const FastTriangle& t, const PixelRect& r, KernelJob& job) {
  EdgeSetup out{EdgeFit::Vector, true};
  job.rect = r;
  job.origin_x = r.x0 & ~7;
  for (int i = 0; i < 3; ++i) {
    const int j = i == 2 ? 0 : i + 1;
    const int64_t xi = t.x_fixed[i], yi = t.y_fixed[i];
    const int64_t dcdx = yi - t.y_fixed[j], dcdy = xi - t.x_fixed[j];  // make_edge(v_i, v_j)
    const int64_t c = dcdx * xi - dcdy * yi + (is_top_left(dcdx, dcdy) ? 1 : 0);
    const int64_t q = (-c) >> 8;  // floor(-c / 256): arithmetic shift (C++20)
    const int64_t g_lo = dcdy * (dcdy >= 0 ? r.y0 : r.y1) - dcdx * (dcdx >= 0 ? r.x1 : r.x0) - q;
    const int64_t g_hi = dcdy * (dcdy >= 0 ? r.y1 : r.y0) - dcdx * (dcdx >= 0 ? r.x0 : r.x1) - q;
    if (g_hi <= 0) return EdgeSetup{};
    if (g_lo > 0) {  // all-in: constant G - 1 = 0 passes the sign test everywhere
      job.g_minus_1[i] = job.gx[i] = job.gy[i] = 0;
      continue;
    }
    out.all_in = false;
    if ((dcdx < 0 ? -dcdx : dcdx) + (dcdy < 0 ? -dcdy : dcdy) > kMaxEdgeStepSum) {
      out.fit = EdgeFit::Scalar;
      continue;
    }
    job.g_minus_1[i] = int32_t(dcdy * r.y0 - dcdx * job.origin_x - q - 1);
    job.gx[i] = int32_t(-dcdx);
    job.gy[i] = int32_t(dcdy);
  }
  return out;
}

}  // namespace rastercmp::cpu::fast
