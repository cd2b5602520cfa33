// Triangle set-up, lp_setup_tri.c (docs/lavapipe-rules.md §2.2-§2.5, §3.2, §4.3; steps 9-15):
// snap to 24.8 → int64 doubled area → drop zero area → facing and cull → make counter-clockwise by
// swapping v1/v2 → edges with the top-left bias → bounding box against the draw region → depth plane
// and bias. Takes window coordinates of one (possibly clipped) triangle in emit order.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>

#include "cpu_raster/exact/raster_primitive.hpp"
#include "cpu_raster/exact/setup_context.hpp"
#include "cpu_raster/exact/viewport.hpp"

namespace rastercmp::cpu {

enum class SetupFate {
  Rasterized,
  NonFinite,      // a coordinate does not snap (NaN, Inf or beyond the 24.8 bound)
  Degenerate,     // zero fixed-point area (triangles) or zero length (lines): always dropped
  Culled,         // the face is culled
  OutsideRegion,  // the bounding box misses the draw region
};

struct TriangleSetup {
  SetupFate fate = SetupFate::Rasterized;
  int64_t area = 0;  // doubled signed area in fixed units^2, before the swap
  bool front_facing = false;
  bool swapped = false;    // v1 and v2 were exchanged to make the triangle counter-clockwise
  PixelRect bbox;          // unclamped bounding box, valid once snapped
  RasterPrimitive raster;  // valid when Rasterized (and partly filled before)
};

// Whether the cull mode drops a triangle of this facing (§2.3).
bool face_culled(bool front_facing, CullMode cull);

// setup_triangle's steps, for the fast path's lean set-up of clipped pieces (setup_piece):
// the three corners snapped (§2.2; nullopt when one does not snap), the doubled area
// dx01*dy20 - dx20*dy01 (§2.3, > 0 is llvmpipe's "ccw"), and do_triangle_ccw's box
// x0 = min >> 8, x1 = (max - 1) >> 8 (§2.5), inside the direct range.
std::optional<std::array<FixedPoint, 3>> snap_triangle(const std::array<WindowVertex, 3>& window, float pixel_offset,
                                                       SnapRounding rounding);
int64_t doubled_area(const std::array<FixedPoint, 3>& v);
inline PixelRect triangle_bbox(const std::array<FixedPoint, 3>& v) {
  const auto [min_x, max_x] = std::minmax({v[0].x.raw, v[1].x.raw, v[2].x.raw});
  const auto [min_y, max_y] = std::minmax({v[0].y.raw, v[1].y.raw, v[2].y.raw});
  return PixelRect{min_x >> kFixedOrder, min_y >> kFixedOrder, (max_x - 1) >> kFixedOrder, (max_y - 1) >> kFixedOrder};
}

TriangleSetup setup_triangle(const std::array<WindowVertex, 3>& window, uint32_t owner, const SetupContext& context);

}  // namespace rastercmp::cpu
