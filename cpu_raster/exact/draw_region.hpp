// Where lavapipe lets a primitive write (docs/lavapipe-rules.md §2.5, step 12-13):
//  - the draw region: framebuffer ∩ scissor ∩ the viewport's pixel rectangle "vpwh";
//  - the scissor planes llvmpipe adds only where the primitive's bounding box crosses the region,
//    with the multisample quirk (left/top planes shifted by 127/256 px);
//  - the pixels its rasterizer visits at all, which follow from how set-up bins the primitive into
//    64x64 tiles (lp_setup_tri.c lp_setup_bin_triangle). Coverage is "all planes E > 0" inside
//    that area; the area only matters where the planes leave samples outside the region (the
//    multisample quirk, line bounding boxes rounded up).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>

#include "cpu_raster/exact/edge_plane.hpp"
#include "cpu_raster/exact/viewport.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

// Inclusive pixel rectangle (Mesa's u_rect); empty when x1 < x0 or y1 < y0.
struct PixelRect {
  int32_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x1 < x0 || y1 < y0; }
  bool contains(int32_t x, int32_t y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
  friend bool operator==(const PixelRect&, const PixelRect&) = default;
};

// Inline, as the small helpers below: set-up calls them for every primitive.
inline PixelRect intersect(const PixelRect& a, const PixelRect& b) {
  return PixelRect{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

// u_rect_test_intersection: the bounds overlap and neither rectangle is empty (x1 < x0 or
// y1 < y0): an empty draw region or line box never intersects (docs/lavapipe-rules.md §2.5).
inline bool rects_touch(const PixelRect& a, const PixelRect& b) {
  return !(a.empty() || b.empty() || a.x1 < b.x0 || b.x1 < a.x0 || a.y1 < b.y0 || b.y1 < a.y0);
}

// lp_setup_set_viewports: the viewport's pixel rectangle, from float translate/scale.
PixelRect viewport_pixel_rect(const ViewportTransform& viewport);

// lp_setup.c try_update_scene_state: framebuffer ∩ scissor ∩ vpwh.
PixelRect draw_region(const Scene& scene, const ViewportTransform& viewport);

// lp_setup_add_scissor_planes, for the region edges `bbox` crosses; appended to `planes`. With
// `sample_exact` (Mesa 25.3, lavapipe-rules §8.6) a sample passes iff its pixel is in the region,
// at every sample count; without, the 4x planes let samples of the column and row before it pass.
void add_scissor_planes(const PixelRect& bbox, const PixelRect& region, bool multisample, PlaneSet& planes,
                        bool sample_exact = false);

// The pixels lavapipe's rasterizer evaluates for a primitive with this (non-negative-clamped)
// bounding box: its 64x64 tile, or the tiles of the box's part inside the region.
// lp_setup_bin_triangle: a box inside one 64x64 tile is binned to that tile. (The 4x4 and 16x16
// "contained" commands it may pick instead cover the triangle's own box, which bounds every
// sample a 3-plane triangle can cover; for 4-plane lines the driver covers samples anywhere in
// the tile, as the 4x line differential tests show.) dx: lp_setup_tri.c floor_pot, the largest
// power of two <= n (0 for 0), which is std::bit_floor.
inline PixelRect binned_area(const PixelRect& bbox, const PixelRect& region) {
  constexpr int32_t kTileSize = 64;  // lp_limits.h TILE_SIZE
  const int32_t dx = int32_t(std::bit_floor(uint32_t((bbox.x0 ^ bbox.x1) | (bbox.y0 ^ bbox.y1))));
  if (dx < kTileSize) {
    const int32_t x = bbox.x0 / kTileSize * kTileSize, y = bbox.y0 / kTileSize * kTileSize;
    return PixelRect{x, y, x + kTileSize - 1, y + kTileSize - 1};
  }
  const PixelRect trimmed = intersect(bbox, region);  // otherwise the tiles of bbox ∩ draw region
  return PixelRect{trimmed.x0 / kTileSize * kTileSize, trimmed.y0 / kTileSize * kTileSize,
                   trimmed.x1 / kTileSize * kTileSize + kTileSize - 1,
                   trimmed.y1 / kTileSize * kTileSize + kTileSize - 1};
}

}  // namespace rastercmp::cpu
