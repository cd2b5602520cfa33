#include "cpu_raster/exact/fixed_point.hpp"

#include <cmath>

namespace rastercmp::cpu {

int32_t snap_vertex_saturating(float x_window, float pixel_offset, SnapRounding rounding) {
  const float rounded = snapped_float(x_window, pixel_offset, rounding);
  constexpr float kTwo31 = 2147483648.0f;
  if (!(rounded >= -kTwo31 && rounded < kTwo31)) return INT32_MIN;  // NaN too
  return static_cast<int32_t>(rounded);
}

std::optional<int32_t> util_iround(float value) {
  const float biased = value >= 0.0f ? value + 0.5f : value - 0.5f;  // rounded float add
  return bounded_int32(std::trunc(biased));
}

std::optional<int32_t> line_snap(float value_pixels) { return util_iround(float(kFixedOne) * value_pixels); }

}  // namespace rastercmp::cpu
