#include "cpu_raster/exact/raster_primitive.hpp"

#include <algorithm>

namespace rastercmp::cpu {
namespace {

int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Pixels with a sample (offsets 0..255 fixed units) inside the vertices' x/y extent.
PixelRect reachable_pixels(const RasterPrimitive& p) {
  const uint32_t n = p.is_line ? 4 : 3;
  int64_t min_x = p.vertex_fixed[0].x.wide(), max_x = min_x;
  int64_t min_y = p.vertex_fixed[0].y.wide(), max_y = min_y;
  for (uint32_t i = 1; i < n; ++i) {
    min_x = std::min(min_x, p.vertex_fixed[i].x.wide());
    max_x = std::max(max_x, p.vertex_fixed[i].x.wide());
    min_y = std::min(min_y, p.vertex_fixed[i].y.wide());
    max_y = std::max(max_y, p.vertex_fixed[i].y.wide());
  }
  return PixelRect{int32_t(floor_div(min_x - (kFixedOne - 1), kFixedOne)),
                   int32_t(floor_div(min_y - (kFixedOne - 1), kFixedOne)), int32_t(floor_div(max_x, kFixedOne)),
                   int32_t(floor_div(max_y, kFixedOne))};
}

}  // namespace

SamplePoint sample_point(int32_t px, int32_t py, uint32_t sample, bool per_sample) {
  SamplePoint point{int64_t(px) * kFixedOne, int64_t(py) * kFixedOne, float(px), float(py)};
  if (per_sample) {  // lp_rast_tri_tmp.h MULTISAMPLE; depth at px + sx (§3.3, §6)
    const SampleOffset& offset = kStandardSamples4x[sample];
    point.x_fixed += offset.x_fixed;
    point.y_fixed += offset.y_fixed;
    point.x += offset.x;
    point.y += offset.y;
  }
  return point;
}

bool place_in_region(RasterPrimitive& p, const PixelRect& bbox, const PixelRect& region, const PixelRect& framebuffer,
                     bool multisample, bool binned, bool sample_exact_scissor) {
  // u_rect_test_intersection rejects empty rectangles: an empty draw region (a scissor of width or
  // height 0, a viewport rectangle that rounds to no pixel) draws nothing, although the multisample
  // planes would pass samples of the column and row just before it, and so does a line whose
  // rounded-up box is empty, although its quad holds samples (docs/lavapipe-rules.md §2.5, §5.3).
  if (!rects_touch(region, bbox)) return false;
  p.bbox = bbox;
  p.bbox.x0 = std::max(p.bbox.x0, 0);  // "can safely discard negative regions"
  p.bbox.y0 = std::max(p.bbox.y0, 0);
  add_scissor_planes(p.bbox, region, multisample, p.planes, sample_exact_scissor);
  // Samples outside the region are reachable only in the column and row just before it (the
  // multisample scissor quirk, line boxes rounded up); right and bottom are exact (§2.5).
  const PixelRect region_and_quirk{region.x0 - 1, region.y0 - 1, region.x1, region.y1};
  p.visit = intersect(binned_area(p.bbox, region), framebuffer);
  if (!binned) p.visit = intersect(p.visit, reachable_pixels(p));
  p.visit = intersect(p.visit, region_and_quirk);
  return true;
}

}  // namespace rastercmp::cpu
