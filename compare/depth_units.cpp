#include "compare/depth_units.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>

#include "model/depth_format.hpp"
#include "model/render_result.hpp"

namespace rastercmp {
namespace {

// Maps float bits to integers that are ordered like the floats (+0 and -0 both map to 0),
// so the integer distance counts the representable floats in between.
int64_t float_order_key(uint32_t bits) {
  const int64_t magnitude = bits & 0x7FFFFFFFu;
  return (bits & 0x80000000u) ? -magnitude : magnitude;
}

}  // namespace

const char* depth_unit_name(DepthFormat format) {
  switch (depth_format_info(format).encoding) {
    case DepthEncoding::Unorm: return "LSB";
    case DepthEncoding::Float: return "ULP";
    case DepthEncoding::None: break;
  }
  return "";
}

uint64_t depth_diff_raw_units(DepthFormat format, uint32_t expected_raw, uint32_t actual_raw) {
  const DepthFormatInfo info = depth_format_info(format);
  switch (info.encoding) {
    case DepthEncoding::Unorm: {
      const int64_t e = expected_raw & info.raw_mask, a = actual_raw & info.raw_mask;
      return uint64_t(std::llabs(e - a));
    }
    case DepthEncoding::Float: return uint64_t(std::llabs(float_order_key(expected_raw) - float_order_key(actual_raw)));
    case DepthEncoding::None: break;
  }
  return 0;
}

double depth_bias_r(DepthFormat format, uint32_t expected_raw, uint32_t actual_raw) {
  const DepthFormatInfo info = depth_format_info(format);
  switch (info.encoding) {
    case DepthEncoding::Unorm: return 2.0 * info.mrd;  // docs/lavapipe-rules.md §4.3: r = 2 * mrd
    case DepthEncoding::Float: {
      // Spec "Depth Bias": r = 2^(e - n) for floating-point formats (docs/lavapipe-rules.md §4.1).
      const double larger = std::fmax(std::fabs(double(std::bit_cast<float>(expected_raw))),
                                      std::fabs(double(std::bit_cast<float>(actual_raw))));
      return float_depth_r(info, larger);
    }
    case DepthEncoding::None: break;
  }
  return 0.0;
}

double depth_diff_r_units(DepthFormat format, uint32_t expected_raw, uint32_t actual_raw) {
  if (format == DepthFormat::None) return 0.0;
  // UNORM: one LSB is 1/(2^n - 1) and r is two of them, exactly.
  if (is_unorm(format)) return double(depth_diff_raw_units(format, expected_raw, actual_raw)) / 2.0;
  const double diff = std::fabs(depth_raw_to_value(format, expected_raw) - depth_raw_to_value(format, actual_raw));
  if (!std::isfinite(diff)) return double(depth_diff_raw_units(format, expected_raw, actual_raw));
  return diff / depth_bias_r(format, expected_raw, actual_raw);
}

}  // namespace rastercmp
