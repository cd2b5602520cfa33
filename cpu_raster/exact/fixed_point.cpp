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

int32_t util_iround_lrintf(float value) {
  constexpr float kTwo63 = 9223372036854775808.0f;
  if (!(std::fabs(value) < kTwo63)) return 0;  // NaN, Inf, out of int64: cvtss2si's 0x8000000000000000
  const auto wide = static_cast<int64_t>(round_nearest_even(value));
  return static_cast<int32_t>(static_cast<uint32_t>(static_cast<uint64_t>(wide)));  // (int) of a long
}

int32_t line_snap_lrintf(float value_pixels) { return util_iround_lrintf(float(kFixedOne) * value_pixels); }

}  // namespace rastercmp::cpu
