#include "model/render_result.hpp"

#include <bit>
#include <stdexcept>

namespace rastercmp {

// Vulkan spec "Fixed-Point Data Conversions": an n-bit UNORM value k stands for k / (2^n - 1).
// Bits above the format's width (the X8 padding of X8_D24) carry no depth and are ignored.
double depth_raw_to_value(DepthFormat format, uint32_t raw) {
  switch (format) {
    case DepthFormat::D16Unorm: return double(raw & 0xFFFFu) / 65535.0;
    case DepthFormat::X8D24Unorm: return double(raw & 0xFFFFFFu) / 16777215.0;
    case DepthFormat::D32Sfloat: return double(std::bit_cast<float>(raw));
    case DepthFormat::None: break;
  }
  throw std::invalid_argument("depth_raw_to_value: the depth format is none, there is no depth to decode");
}

}  // namespace rastercmp
