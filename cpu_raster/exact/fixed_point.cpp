#include "cpu_raster/exact/fixed_point.hpp"

#include <cmath>

namespace rastercmp::cpu {
namespace {

// Only integers that int32 holds and the set-up bound accepts come back.
std::optional<int32_t> to_int32(float integral_value) {
  if (!(std::fabs(integral_value) <= float(Fixed24_8::kMaxMagnitude))) return std::nullopt;
  return static_cast<int32_t>(integral_value);
}

// fl(fl(x - offset) * 256), rounded to an integral float.
float snapped_float(float x_window, float pixel_offset, SnapRounding rounding) {
  const float shifted = x_window - pixel_offset;                         // a float subtraction first (§2.2)
  const float scaled = shifted * float(kFixedOne);                       // exact: a power of two
  return rounding == SnapRounding::NearestEven ? std::nearbyint(scaled)  // default rounding mode: to nearest even
                                               : std::round(scaled);     // half away from zero
}

}  // namespace

int32_t snap_vertex_saturating(float x_window, float pixel_offset, SnapRounding rounding) {
  const float rounded = snapped_float(x_window, pixel_offset, rounding);
  constexpr float kTwo31 = 2147483648.0f;
  if (!(rounded >= -kTwo31 && rounded < kTwo31)) return INT32_MIN;  // NaN too
  return static_cast<int32_t>(rounded);
}

std::optional<Fixed24_8> snap_vertex(float x_window, float pixel_offset, SnapRounding rounding) {
  const float rounded = snapped_float(x_window, pixel_offset, rounding);
  const std::optional<int32_t> raw = to_int32(rounded);
  if (!raw) return std::nullopt;
  return Fixed24_8{*raw};
}

std::optional<int32_t> util_iround(float value) {
  const float biased = value >= 0.0f ? value + 0.5f : value - 0.5f;  // rounded float add
  return to_int32(std::trunc(biased));
}

std::optional<int32_t> line_snap(float value_pixels) { return util_iround(float(kFixedOne) * value_pixels); }

}  // namespace rastercmp::cpu
