// The union of all draws, per pixel: Must if some primitive certainly covers the pixel's box and
// is certainly written (or a shared-edge pair does), May if some primitive possibly does, MustNot
// otherwise. Pixels outside the framebuffer ∩ scissor are MustNot, exactly (Vulkan "Scissor Test":
// samples outside the scissor rectangle get coverage 0). Multisample pixels are judged as a whole
// (see subpixel.hpp), so every sample of a pixel gets the pixel's class.
#pragma once

#include <cstdint>
#include <vector>

#include "cpu_raster/exact/draw_region.hpp"
#include "cpu_raster/spec/depth_gate.hpp"
#include "cpu_raster/spec/triangle_coverage.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::spec {

// framebuffer ∩ scissor, inclusive pixel bounds (empty for a zero-sized scissor).
PixelRect scissor_region(const Scene& scene);

class CoverageMap {
 public:
  explicit CoverageMap(const Scene& scene);

  const PixelRect& region() const { return region_; }
  // One primitive's coverage of pixel (px, py), inside region().
  void add(int32_t px, int32_t py, Coverage coverage, Gate gate);
  void make_must(int32_t px, int32_t py);
  void make_may_everywhere();
  bool is_must(int32_t px, int32_t py) const;

  // Per sample, in RenderResult order.
  std::vector<CoverageClass> classes() const;

 private:
  size_t pixel(int32_t px, int32_t py) const { return size_t(py) * width_ + size_t(px); }

  uint32_t width_ = 0, samples_ = 1;
  PixelRect region_;
  std::vector<CoverageClass> pixel_class_;  // per pixel, starts MustNot
};

}  // namespace rastercmp::cpu::spec
