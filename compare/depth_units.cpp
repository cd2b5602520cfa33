#include "compare/depth_units.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>

#include "model/render_result.hpp"

namespace rastercmp {
namespace {

uint32_t unorm_mask(DepthFormat format) { return format == DepthFormat::D16Unorm ? 0xFFFFu : 0xFFFFFFu; }

// Maps float bits to integers that are ordered like the floats (+0 and -0 both map to 0),
// so the integer distance counts the representable floats in between.
int64_t float_order_key(uint32_t bits) {
  const int64_t magnitude = bits & 0x7FFFFFFFu;
  return (bits & 0x80000000u) ? -magnitude : magnitude;
}

}  // namespace

const char* depth_unit_name(DepthFormat format) {
  switch (format) {
    case DepthFormat::D16Unorm:
    case DepthFormat::X8D24Unorm: return "LSB";
    case DepthFormat::D32Sfloat: return "ULP";
    case DepthFormat::None: break;
  }
  return "";
}

uint64_t depth_diff_raw_units(DepthFormat format, uint32_t expected_raw, uint32_t actual_raw) {
  switch (format) {
    case DepthFormat::D16Unorm:
    case DepthFormat::X8D24Unorm: {
      const int64_t e = expected_raw & unorm_mask(format), a = actual_raw & unorm_mask(format);
      return uint64_t(std::llabs(e - a));
    }
    case DepthFormat::D32Sfloat:
      return uint64_t(std::llabs(float_order_key(expected_raw) - float_order_key(actual_raw)));
    case DepthFormat::None: break;
  }
  return 0;
}

double depth_bias_r(DepthFormat format, uint32_t expected_raw, uint32_t actual_raw) {
  switch (format) {
    case DepthFormat::D16Unorm: return 2.0 / 65535.0;       // docs/lavapipe-rules.md §4.3: r = 2 * mrd
    case DepthFormat::X8D24Unorm: return 2.0 / 16777215.0;  // docs/lavapipe-rules.md §4.3: r = 2 * mrd
    case DepthFormat::D32Sfloat: {
      // Spec "Depth Bias": r = 2^(e - n) for floating-point formats, n = 23 mantissa bits.
      const double larger = std::fmax(std::fabs(double(std::bit_cast<float>(expected_raw))),
                                      std::fabs(double(std::bit_cast<float>(actual_raw))));
      int exponent_frexp = 0;
      std::frexp(larger, &exponent_frexp);  // larger = m * 2^E, m in [0.5, 1): e = E - 1
      const int e = (larger == 0.0 || !std::isfinite(larger)) ? -126 : std::max(exponent_frexp - 1, -126);
      return std::ldexp(1.0, e - 23);
    }
    case DepthFormat::None: break;
  }
  return 0.0;
}

double depth_diff_r_units(DepthFormat format, uint32_t expected_raw, uint32_t actual_raw) {
  if (format == DepthFormat::None) return 0.0;
  // UNORM: one LSB is 1/(2^n - 1) and r is two of them, exactly.
  if (format != DepthFormat::D32Sfloat) return double(depth_diff_raw_units(format, expected_raw, actual_raw)) / 2.0;
  const double diff = std::fabs(depth_raw_to_value(format, expected_raw) - depth_raw_to_value(format, actual_raw));
  if (!std::isfinite(diff)) return double(depth_diff_raw_units(format, expected_raw, actual_raw));
  return diff / depth_bias_r(format, expected_raw, actual_raw);
}

}  // namespace rastercmp
