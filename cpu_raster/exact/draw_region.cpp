#include "cpu_raster/exact/draw_region.hpp"

#include <algorithm>
#include <cmath>

namespace rastercmp::cpu {
namespace {

// u_rect_possible_intersection; an empty result stays empty.
PixelRect possible_intersection(const PixelRect& a, const PixelRect& b) {
  return rects_touch(a, b) ? intersect(a, b) : PixelRect{};
}

}  // namespace

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

}  // namespace rastercmp::cpu
