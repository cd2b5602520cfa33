#include "cpu_raster/exact/draw_region.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace rastercmp::cpu {
namespace {

constexpr int32_t kTileSize = 64;  // lp_limits.h TILE_SIZE

PixelRect square_at(int32_t x, int32_t y, int32_t size) { return PixelRect{x, y, x + size - 1, y + size - 1}; }

// u_rect_possible_intersection; an empty result stays empty.
PixelRect possible_intersection(const PixelRect& a, const PixelRect& b) {
  return rects_touch(a, b) ? intersect(a, b) : PixelRect{};
}

}  // namespace

PixelRect intersect(const PixelRect& a, const PixelRect& b) {
  return PixelRect{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

bool rects_touch(const PixelRect& a, const PixelRect& b) {
  return !(a.empty() || b.empty() || a.x1 < b.x0 || b.x1 < a.x0 || a.y1 < b.y0 || b.y1 < a.y0);
}

PixelRect viewport_pixel_rect(const ViewportTransform& v) {
  const float x0 = v.translate[0] - v.scale[0];  // docs/lavapipe-rules.md §2.5, each a float operation
  const float y0 = v.translate[1] - std::fabs(v.scale[1]);
  return PixelRect{static_cast<int32_t>(x0 + 0.499f), static_cast<int32_t>(y0 + 0.499f),
                   static_cast<int32_t>(v.scale[0] * 2.0f + x0 - 0.501f),
                   static_cast<int32_t>(std::fabs(v.scale[1]) * 2.0f + y0 - 0.501f)};
}

PixelRect draw_region(const Scene& scene, const ViewportTransform& viewport) {
  PixelRect region{0, 0, int32_t(scene.width) - 1, int32_t(scene.height) - 1};
  const Rect2D scissor = scene.effective_scissor();  // lavapipe always enables the scissor test
  const int64_t scissor_x1 = int64_t(scissor.x) + scissor.width - 1;
  const int64_t scissor_y1 = int64_t(scissor.y) + scissor.height - 1;
  const PixelRect scissor_rect{scissor.x, scissor.y, int32_t(std::min<int64_t>(scissor_x1, INT32_MAX)),
                               int32_t(std::min<int64_t>(scissor_y1, INT32_MAX))};
  region = possible_intersection(scissor_rect, region);
  return possible_intersection(viewport_pixel_rect(viewport), region);  // point_tri_clip: always
}

void add_scissor_planes(const PixelRect& bbox, const PixelRect& r, bool multisample, PlaneSet& planes,
                        bool sample_exact) {
  const int64_t one = kFixedOne;
  if (sample_exact) {  // left and top inclusive, right and bottom exclusive pixel edges (§8.6)
    if (bbox.x0 < r.x0) planes.push(EdgePlane{-(r.x0 * one) + 1, -1, 0, false});          // left
    if (bbox.x1 > r.x1) planes.push(EdgePlane{(int64_t(r.x1) + 1) * one, 1, 0, false});   // right
    if (bbox.y0 < r.y0) planes.push(EdgePlane{-(r.y0 * one) + 1, 0, 1, false});           // top
    if (bbox.y1 > r.y1) planes.push(EdgePlane{(int64_t(r.y1) + 1) * one, 0, -1, false});  // bottom
    return;
  }
  const int64_t adj = multisample ? 127 : 0;                                            // the MSAA quirk of §2.5
  if (bbox.x0 < r.x0) planes.push(EdgePlane{-((r.x0 - 1) * one + adj), -1, 0, false});  // left
  if (bbox.x1 > r.x1) planes.push(EdgePlane{r.x1 * one + 127 + adj, 1, 0, false});      // right
  if (bbox.y0 < r.y0) planes.push(EdgePlane{-((r.y0 - 1) * one + adj), 0, 1, false});   // top
  if (bbox.y1 > r.y1) planes.push(EdgePlane{r.y1 * one + 127 + adj, 0, -1, false});     // bottom
}

PixelRect binned_area(const PixelRect& bbox, const PixelRect& region) {
  // lp_setup_bin_triangle: a box inside one 64x64 tile is binned to that tile. (The 4x4 and 16x16
  // "contained" commands it may pick instead cover the triangle's own box, which bounds every
  // sample a 3-plane triangle can cover; for 4-plane lines the driver covers samples anywhere in
  // the tile, as the 4x line differential tests show.) dx: lp_setup_tri.c floor_pot, the largest
  // power of two <= n (0 for 0), which is std::bit_floor.
  const int32_t dx = int32_t(std::bit_floor(uint32_t((bbox.x0 ^ bbox.x1) | (bbox.y0 ^ bbox.y1))));
  if (dx < kTileSize) return square_at(bbox.x0 / kTileSize * kTileSize, bbox.y0 / kTileSize * kTileSize, kTileSize);
  const PixelRect trimmed = intersect(bbox, region);  // otherwise the tiles of bbox ∩ draw region
  return PixelRect{trimmed.x0 / kTileSize * kTileSize, trimmed.y0 / kTileSize * kTileSize,
                   trimmed.x1 / kTileSize * kTileSize + kTileSize - 1,
                   trimmed.y1 / kTileSize * kTileSize + kTileSize - 1};
}

}  // namespace rastercmp::cpu
