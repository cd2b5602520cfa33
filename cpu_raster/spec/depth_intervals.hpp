// Per pixel, the raw depth values any conformant device may store (docs/spec-profile.md "Depth
// intervals"): the hull over every primitive that may write the sample of the range its fragment
// may have there (fragment_depth_range), and the clear value unless some depth-writing primitive
// certainly covers the sample and certainly passes against it, converted to the format with either
// rounding. The stored value is the depth of the last fragment that passed, or the clear value, so
// it lies in that hull whatever the order of passes. Every sample of a pixel gets the pixel's
// interval (multisample pixels are judged as a whole, subpixel.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "cpu_raster/exact/draw_region.hpp"
#include "cpu_raster/spec/depth_gate.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::spec {

class DepthIntervalMap {
 public:
  explicit DepthIntervalMap(const Scene& scene);

  // A primitive that may write pixel (px, py) with a fragment depth in `range`; `certain`: it
  // certainly covers the pixel's samples and certainly passes against the clear value.
  void add(int32_t px, int32_t py, const DepthValueRange& range, bool certain);
  // Every pixel of `region` may hold any value (an undefined primitive).
  void make_any(const PixelRect& region);

  // Per sample, in RenderResult order; empty for a scene without depth.
  std::vector<DepthInterval> intervals() const;

 private:
  struct Pixel {
    bool written = false;  // some range was added
    bool certain = false;  // the clear value cannot remain
    DepthValueRange range;
  };
  size_t pixel(int32_t px, int32_t py) const { return size_t(py) * width_ + size_t(px); }

  DepthFormat format_ = DepthFormat::None;
  double clear_ = 1;
  uint32_t width_ = 0, samples_ = 1;
  std::vector<Pixel> pixels_;
};

}  // namespace rastercmp::cpu::spec
