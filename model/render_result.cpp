#include "model/render_result.hpp"

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

}  // namespace rastercmp
