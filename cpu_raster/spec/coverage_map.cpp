#include "cpu_raster/spec/coverage_map.hpp"

#include <algorithm>

namespace rastercmp::cpu::spec {

PixelRect scissor_region(const Scene& scene) {
  const Rect2D s = scene.effective_scissor();
  if (s.width == 0 || s.height == 0) return PixelRect{};
  const int64_t x1 = std::min<int64_t>(int64_t(s.x) + s.width - 1, int64_t(scene.width) - 1);
  const int64_t y1 = std::min<int64_t>(int64_t(s.y) + s.height - 1, int64_t(scene.height) - 1);
  return PixelRect{std::max(s.x, 0), std::max(s.y, 0), int32_t(x1), int32_t(y1)};
}

CoverageMap::CoverageMap(const Scene& scene)
    : width_(scene.width),
      samples_(scene.samples),
      region_(scissor_region(scene)),
      pixel_class_(size_t(scene.width) * scene.height, CoverageClass::MustNot) {}

void CoverageMap::add(int32_t px, int32_t py, Coverage coverage, Gate gate) {
  if (coverage == Coverage::None || gate == Gate::Never) return;
  CoverageClass& c = pixel_class_[pixel(px, py)];
  const CoverageClass mine =
      (coverage == Coverage::Full && gate == Gate::Certain) ? CoverageClass::Must : CoverageClass::May;
  c = std::max(c, mine);
}

void CoverageMap::make_must(int32_t px, int32_t py) { pixel_class_[pixel(px, py)] = CoverageClass::Must; }

void CoverageMap::make_may_everywhere() {
  for (int32_t py = region_.y0; py <= region_.y1; ++py)
    for (int32_t px = region_.x0; px <= region_.x1; ++px) add(px, py, Coverage::Partial, Gate::Maybe);
}

bool CoverageMap::is_must(int32_t px, int32_t py) const { return pixel_class_[pixel(px, py)] == CoverageClass::Must; }

std::vector<CoverageClass> CoverageMap::classes() const {
  std::vector<CoverageClass> out;
  out.reserve(pixel_class_.size() * samples_);
  for (const CoverageClass c : pixel_class_) out.insert(out.end(), samples_, c);
  return out;
}

}  // namespace rastercmp::cpu::spec
