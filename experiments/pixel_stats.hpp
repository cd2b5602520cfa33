// Per-pixel measures over RenderResults: which surface won, what changed, whether two agree.
#pragma once

#include <cstdint>
#include <vector>

#include "model/render_result.hpp"

namespace rastercmp::experiments {

// Pixels (sample 0) some primitive of the result covers.
std::vector<bool> covered_mask(const RenderResult& result);
size_t count(const std::vector<bool>& mask);

// Fraction of `mask` pixels whose owner is not draw `decal_draw` (0 when the mask is empty).
double wrong_surface_fraction(const RenderResult& result, const std::vector<bool>& mask, uint32_t decal_draw);

// Fraction of `mask` pixels whose owner differs between two renders of the same size.
double owner_change_fraction(const RenderResult& a, const RenderResult& b, const std::vector<bool>& mask);

struct Mismatch {
  size_t coverage = 0;  // samples whose owner differs
  size_t depth = 0;     // samples whose raw depth differs
  size_t samples = 0;
  bool identical() const { return coverage == 0 && depth == 0; }
};
// Throws std::invalid_argument when the sizes differ.
Mismatch compare_results(const RenderResult& a, const RenderResult& b);

}  // namespace rastercmp::experiments
