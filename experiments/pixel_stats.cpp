#include "experiments/pixel_stats.hpp"

#include <stdexcept>

namespace rastercmp::experiments {

std::vector<bool> covered_mask(const RenderResult& result) {
  std::vector<bool> mask(size_t(result.width) * result.height);
  for (uint32_t y = 0; y < result.height; ++y)
    for (uint32_t x = 0; x < result.width; ++x)
      mask[size_t(y) * result.width + x] = result.owner[result.index(x, y)] != kOwnerBackground;
  return mask;
}

size_t count(const std::vector<bool>& mask) {
  size_t n = 0;
  for (bool m : mask) n += m ? 1 : 0;
  return n;
}

double wrong_surface_fraction(const RenderResult& result, const std::vector<bool>& mask, uint32_t decal_draw) {
  size_t wrong = 0, total = 0;
  for (size_t p = 0; p < mask.size(); ++p) {
    if (!mask[p]) continue;
    ++total;
    const uint32_t owner = result.owner[p * result.samples];
    if (owner == kOwnerBackground || owner_draw(owner) != decal_draw) ++wrong;
  }
  return total ? double(wrong) / double(total) : 0.0;
}

double owner_change_fraction(const RenderResult& a, const RenderResult& b, const std::vector<bool>& mask) {
  if (a.owner.size() != b.owner.size()) throw std::invalid_argument("renders of different sizes");
  size_t changed = 0, total = 0;
  for (size_t p = 0; p < mask.size(); ++p) {
    if (!mask[p]) continue;
    ++total;
    if (a.owner[p * a.samples] != b.owner[p * b.samples]) ++changed;
  }
  return total ? double(changed) / double(total) : 0.0;
}

Mismatch compare_results(const RenderResult& a, const RenderResult& b) {
  if (a.owner.size() != b.owner.size() || a.depth_raw.size() != b.depth_raw.size())
    throw std::invalid_argument("renders of different sizes");
  Mismatch m;
  m.samples = a.owner.size();
  for (size_t i = 0; i < a.owner.size(); ++i) m.coverage += a.owner[i] != b.owner[i] ? 1 : 0;
  for (size_t i = 0; i < a.depth_raw.size(); ++i) m.depth += a.depth_raw[i] != b.depth_raw[i] ? 1 : 0;
  return m;
}

}  // namespace rastercmp::experiments
