#include "model/render_result.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include "model/depth_format.hpp"

namespace rastercmp {

// Vulkan spec "Fixed-Point Data Conversions": an n-bit UNORM value k stands for k / (2^n - 1).
// Bits above the format's width (the X8 padding of X8_D24) carry no depth and are ignored.
double depth_raw_to_value(DepthFormat format, uint32_t raw) {
  const DepthFormatInfo info = depth_format_info(format);
  switch (info.encoding) {
    case DepthEncoding::Unorm: return double(raw & info.raw_mask) / double(unorm_max(info));
    case DepthEncoding::Float: return double(std::bit_cast<float>(raw));
    case DepthEncoding::None: break;
  }
  throw std::invalid_argument("depth_raw_to_value: the depth format is none, there is no depth to decode");
}

int64_t depth_raw_order(DepthFormat format, uint32_t raw) {
  const DepthFormatInfo info = depth_format_info(format);
  if (info.encoding == DepthEncoding::Float) {
    const int64_t magnitude = raw & 0x7FFFFFFFu;
    return (raw & 0x80000000u) ? -magnitude : magnitude;
  }
  return int64_t(raw & info.raw_mask);
}

bool depth_in_interval(DepthFormat format, const DepthInterval& interval, uint32_t raw) {
  if (interval.any) return true;
  const int64_t key = depth_raw_order(format, raw);
  return key >= depth_raw_order(format, interval.lo_raw) && key <= depth_raw_order(format, interval.hi_raw);
}

bool is_owner_alternative(const RenderResult& result, size_t index, uint32_t owner) {
  const OwnerAlternative key{uint64_t(index), owner};
  const auto less = [](const OwnerAlternative& a, const OwnerAlternative& b) {
    return a.sample != b.sample ? a.sample < b.sample : a.owner < b.owner;
  };
  return std::binary_search(result.owner_alternatives.begin(), result.owner_alternatives.end(), key, less);
}

const char* to_string(DepthTerm term) {
  switch (term) {
    case DepthTerm::Plane: return "the plane through the vertices";
    case DepthTerm::Snapping: return "vertex snapping";
    case DepthTerm::Bias: return "depth bias";
    case DepthTerm::Precision: return "floating-point precision";
    case DepthTerm::Rounding: return "rounding to the format";
    case DepthTerm::Clear: return "the clear value";
    case DepthTerm::Undefined: return "undefined depth";
  }
  return "?";
}

}  // namespace rastercmp
