#include "cpu_raster/spec/depth_intervals.hpp"

namespace rastercmp::cpu::spec {
namespace {

// The hull of two ranges; each end keeps the term of the range it came from.
void widen(DepthValueRange& into, const DepthValueRange& r) {
  if (into.any) return;
  if (r.any) {
    into = r;
    return;
  }
  if (r.lo < into.lo) {
    into.lo = r.lo;
    into.lo_term = r.lo_term;
    into.lo_widening = r.lo_widening;
  }
  if (r.hi > into.hi) {
    into.hi = r.hi;
    into.hi_term = r.hi_term;
    into.hi_widening = r.hi_widening;
  }
}

}  // namespace

DepthIntervalMap::DepthIntervalMap(const Scene& scene)
    : format_(scene.depth_format),
      clear_(scene.depth_clear),
      width_(scene.width),
      samples_(scene.samples),
      pixels_(scene.has_depth() ? size_t(scene.width) * scene.height : 0) {}

void DepthIntervalMap::add(int32_t px, int32_t py, const DepthValueRange& range, bool certain) {
  if (pixels_.empty()) return;
  Pixel& p = pixels_[pixel(px, py)];
  if (p.written)
    widen(p.range, range);
  else
    p.range = range;
  p.written = true;
  p.certain = p.certain || certain;
}

void DepthIntervalMap::make_any(const PixelRect& region) {
  DepthValueRange any;
  any.any = true;
  any.lo_term = any.hi_term = DepthTerm::Undefined;
  for (int32_t py = region.y0; py <= region.y1; ++py)
    for (int32_t px = region.x0; px <= region.x1; ++px) add(px, py, any, false);
}

std::vector<DepthInterval> DepthIntervalMap::intervals() const {
  std::vector<DepthInterval> out;
  if (pixels_.empty()) return out;
  out.reserve(pixels_.size() * samples_);
  DepthValueRange clear;
  clear.lo = clear.hi = clear_;
  clear.lo_term = clear.hi_term = DepthTerm::Clear;
  for (const Pixel& p : pixels_) {
    DepthValueRange range = p.written ? p.range : clear;
    if (p.written && !p.certain) widen(range, clear);
    DepthInterval interval = depth_format_interval(format_, range);
    // The clear value is converted like any other ("Clear Values"), with either rounding.
    if (range.lo_term == DepthTerm::Clear) interval.lo_term = DepthTerm::Clear;
    if (range.hi_term == DepthTerm::Clear) interval.hi_term = DepthTerm::Clear;
    out.insert(out.end(), samples_, interval);
  }
  return out;
}

}  // namespace rastercmp::cpu::spec
