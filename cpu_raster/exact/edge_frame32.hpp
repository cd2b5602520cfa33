// 32-bit edge values over a small pixel box (llvmpipe's use_32bits in lp_setup_tri.c; docs/lavapipe-rules.md
// §2.4: the 32- and 64-bit paths give the same sign). The exact path's rasterizer uses them when the
// primitive's visit rectangle allows it (WorkSkips::edges32_when_box_fits), 64-bit values otherwise.
//
// Relative to the box's first sample position (X0, Y0) = 256 * (visit.x0, visit.y0), the edge value
// at a sample (X, Y) = (X0 + dX, Y0 + dY) is
//     E(X, Y) = c0 + dcdy*dY - dcdx*dX,   c0 = E(X0, Y0)   (edge_plane.hpp edge_value, once in int64),
// the same integer as c + dcdy*Y - dcdx*X, so the test E > 0 is unchanged.
//
// Overflow bound (why every term and partial sum stays below 2^31):
//   - the box is at most kEdges32MaxBoxPixels = 64 px wide and high, so the sample offsets satisfy
//     0 <= dX, dY <= 64*256 - 1 < 2^14 (a 4x sample sits at most 224/256 px into its pixel);
//   - each plane has |dcdx|, |dcdy| <= kEdges32MaxDelta = 2^14: for an edge these are coordinate
//     differences of the primitive's vertices in 24.8 units (vertices within 64 px); scissor planes have 1;
//   - |c0| <= kEdges32MaxC0 = 2^30, checked per plane (one int64 value per plane and primitive).
//   Then |dcdy*dY| and |dcdx*dX| are < 2^28, the partial sum c0 + dcdy*dY is < 2^30 + 2^28 and
//   |E| < 2^30 + 2^29 < 2^31 (static_assert below). A box or plane beyond these limits keeps 64 bits.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>

#include "cpu_raster/exact/draw_region.hpp"
#include "cpu_raster/exact/edge_plane.hpp"

namespace rastercmp::cpu {

inline constexpr int32_t kEdges32MaxBoxPixels = 64;
inline constexpr int64_t kEdges32MaxOffset = int64_t(kEdges32MaxBoxPixels) * kFixedOne - 1;  // dX, dY
inline constexpr int64_t kEdges32MaxDelta = int64_t(1) << 14;                                // |dcdx|, |dcdy|
inline constexpr int64_t kEdges32MaxC0 = int64_t(1) << 30;                                   // |c0|
static_assert(kEdges32MaxOffset < (int64_t(1) << 14), "sample offsets in the box are below 2^14");
static_assert(kEdges32MaxC0 + kEdges32MaxDelta * kEdges32MaxOffset <= std::numeric_limits<int32_t>::max(),
              "c0 + dcdy*dY must fit in int32");
static_assert(kEdges32MaxC0 + 2 * kEdges32MaxDelta * kEdges32MaxOffset <= std::numeric_limits<int32_t>::max(),
              "c0 + dcdy*dY - dcdx*dX must fit in int32");

// A primitive's planes re-based at the box origin, in 32 bits.
struct EdgeFrame32 {
  int64_t x0_fixed = 0, y0_fixed = 0;  // (X0, Y0)
  std::array<int32_t, 8> c0{}, dcdx{}, dcdy{};
  uint32_t count = 0;
};

// nullopt when the box or a plane is beyond the limits above (or the box is empty).
inline std::optional<EdgeFrame32> make_edge_frame32(const PlaneSet& planes, const PixelRect& box) {
  if (box.empty() || int64_t(box.x1) - box.x0 >= kEdges32MaxBoxPixels ||
      int64_t(box.y1) - box.y0 >= kEdges32MaxBoxPixels)
    return std::nullopt;
  EdgeFrame32 frame;
  frame.x0_fixed = int64_t(box.x0) * kFixedOne;
  frame.y0_fixed = int64_t(box.y0) * kFixedOne;
  frame.count = planes.count;
  for (uint32_t i = 0; i < planes.count; ++i) {
    const EdgePlane& plane = planes.plane[i];
    const int64_t c0 = edge_value(plane, frame.x0_fixed, frame.y0_fixed);
    if (plane.dcdx > kEdges32MaxDelta || plane.dcdx < -kEdges32MaxDelta || plane.dcdy > kEdges32MaxDelta ||
        plane.dcdy < -kEdges32MaxDelta || c0 > kEdges32MaxC0 || c0 < -kEdges32MaxC0)
      return std::nullopt;
    frame.c0[i] = int32_t(c0);
    frame.dcdx[i] = int32_t(plane.dcdx);
    frame.dcdy[i] = int32_t(plane.dcdy);
  }
  return frame;
}

// dx_fixed, dy_fixed: the sample's offset from (X0, Y0), each in [0, kEdges32MaxOffset].
inline int32_t edge_value32(const EdgeFrame32& frame, uint32_t i, int32_t dx_fixed, int32_t dy_fixed) {
  return frame.c0[i] + frame.dcdy[i] * dy_fixed - frame.dcdx[i] * dx_fixed;
}

// Index of the first plane whose value is <= 0, or -1 when the sample is covered (as
// first_failing_plane in rasterize.hpp).
inline int first_failing_plane32(const EdgeFrame32& frame, int32_t dx_fixed, int32_t dy_fixed) {
  for (uint32_t i = 0; i < frame.count; ++i)
    if (edge_value32(frame, i, dx_fixed, dy_fixed) <= 0) return int(i);
  return -1;
}

}  // namespace rastercmp::cpu
