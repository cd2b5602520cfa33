#include "vk_reference/vk_translate.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/core.h>

#include "model/depth_format.hpp"
#include "model/errors.hpp"

namespace rastercmp::vk {

// The Vulkan half of the depth-format table (model/depth_format.hpp): no default, so a format
// without a VkFormat does not compile.
VkFormat to_vk_format(DepthFormat format) {
  switch (format) {
    case DepthFormat::D16Unorm: return VK_FORMAT_D16_UNORM;
    case DepthFormat::X8D24Unorm: return VK_FORMAT_X8_D24_UNORM_PACK32;
    case DepthFormat::D32Sfloat: return VK_FORMAT_D32_SFLOAT;
    case DepthFormat::None: break;
  }
  return VK_FORMAT_UNDEFINED;
}

VkPrimitiveTopology to_vk(Topology topology) {
  switch (topology) {
    case Topology::PointList: return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    case Topology::LineList: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    case Topology::LineStrip: return VK_PRIMITIVE_TOPOLOGY_LINE_STRIP;
    case Topology::TriangleList: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    case Topology::TriangleStrip: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    case Topology::TriangleFan: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN;
  }
  return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
}

VkCullModeFlags to_vk(CullMode mode) {
  switch (mode) {
    case CullMode::None: return VK_CULL_MODE_NONE;
    case CullMode::Front: return VK_CULL_MODE_FRONT_BIT;
    case CullMode::Back: return VK_CULL_MODE_BACK_BIT;
    case CullMode::FrontAndBack: return VK_CULL_MODE_FRONT_AND_BACK;
  }
  return VK_CULL_MODE_NONE;
}

VkFrontFace to_vk(FrontFace face) {
  return face == FrontFace::Clockwise ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
}

VkPolygonMode to_vk(PolygonMode mode) {
  switch (mode) {
    case PolygonMode::Fill: return VK_POLYGON_MODE_FILL;
    case PolygonMode::Line: return VK_POLYGON_MODE_LINE;
    case PolygonMode::Point: return VK_POLYGON_MODE_POINT;
  }
  return VK_POLYGON_MODE_FILL;
}

VkCompareOp to_vk(CompareOp op) {
  switch (op) {
    case CompareOp::Never: return VK_COMPARE_OP_NEVER;
    case CompareOp::Less: return VK_COMPARE_OP_LESS;
    case CompareOp::Equal: return VK_COMPARE_OP_EQUAL;
    case CompareOp::LessOrEqual: return VK_COMPARE_OP_LESS_OR_EQUAL;
    case CompareOp::Greater: return VK_COMPARE_OP_GREATER;
    case CompareOp::NotEqual: return VK_COMPARE_OP_NOT_EQUAL;
    case CompareOp::GreaterOrEqual: return VK_COMPARE_OP_GREATER_OR_EQUAL;
    case CompareOp::Always: return VK_COMPARE_OP_ALWAYS;
  }
  return VK_COMPARE_OP_LESS;
}

VkLineRasterizationModeEXT to_vk(LineMode mode) {
  switch (mode) {
    case LineMode::Default: return VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT;
    case LineMode::Rectangular: return VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT;
    case LineMode::Bresenham: return VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT;
    case LineMode::RectangularSmooth: return VK_LINE_RASTERIZATION_MODE_RECTANGULAR_SMOOTH_EXT;
  }
  return VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT;
}

VkSampleCountFlagBits to_vk_samples(uint32_t samples) {
  switch (samples) {
    case 1: return VK_SAMPLE_COUNT_1_BIT;
    case 2: return VK_SAMPLE_COUNT_2_BIT;
    case 4: return VK_SAMPLE_COUNT_4_BIT;
    case 8: return VK_SAMPLE_COUNT_8_BIT;
    case 16: return VK_SAMPLE_COUNT_16_BIT;
    case 32: return VK_SAMPLE_COUNT_32_BIT;
    case 64: return VK_SAMPLE_COUNT_64_BIT;
    default: break;
  }
  throw NotSupportedError("sample count " + std::to_string(samples) + " is not a Vulkan sample count");
}

uint32_t depth_copy_texel_bytes(DepthFormat format) { return depth_format_info(format).bytes_per_texel; }

uint32_t depth_raw_from_copy(DepthFormat format, const unsigned char* texel) {
  // A texel of bytes_per_texel little-endian bytes; the bits outside raw_mask (the X8 of
  // VK_FORMAT_X8_D24_UNORM_PACK32) are undefined and dropped.
  static_assert(std::endian::native == std::endian::little, "a short texel fills the low bytes");
  const DepthFormatInfo info = depth_format_info(format);
  uint32_t bits = 0;
  std::memcpy(&bits, texel, std::min<size_t>(info.bytes_per_texel, sizeof bits));
  return bits & info.raw_mask;
}

const char* to_string(UnormSampling sampling) {
  switch (sampling) {
    case UnormSampling::Quotient: return "r / (2^n - 1), correctly rounded";
    case UnormSampling::ReciprocalProduct: return "float(r) * float(1 / (2^n - 1))";
  }
  return "?";
}

float sampled_unorm(UnormSampling sampling, uint32_t raw, uint32_t max) {
  if (sampling == UnormSampling::Quotient) return static_cast<float>(double(raw) / double(max));  // exact, then rounded
  return static_cast<float>(raw) * static_cast<float>(1.0 / double(max));
}

uint32_t depth_raw_from_sampled(DepthFormat format, UnormSampling sampling, uint32_t float_bits) {
  const DepthFormatInfo info = depth_format_info(format);
  if (info.encoding == DepthEncoding::Float) return float_bits;
  if (info.encoding != DepthEncoding::Unorm) throw std::invalid_argument("depth_raw_from_sampled: no depth format");
  const uint32_t max = info.raw_mask;  // UNORM: 2^bits - 1
  const float sampled = std::bit_cast<float>(float_bits);
  if (sampled >= 0.0f && sampled <= 1.0f) {
    // Either conversion is within one unit (1 / max) of r / max, so every r that converts to
    // `sampled` lies in round(sampled * max) - 1 .. + 1; the largest one wins.
    const int64_t nearest = std::llround(double(sampled) * double(max));
    for (int64_t r = std::min<int64_t>(nearest + 1, max); r >= std::max<int64_t>(nearest - 1, 0); --r) {
      if (sampled_unorm(sampling, static_cast<uint32_t>(r), max) == sampled) return static_cast<uint32_t>(r);
    }
  }
  throw std::runtime_error(fmt::format("sampled {} depth {:#010x} ({}) is no stored value's conversion ({})",
                                       to_string(format), float_bits, double(sampled), to_string(sampling)));
}

namespace {

// [offset, offset + extent) clipped to [0, INT32_MAX]: (offset', extent').
std::pair<int32_t, uint32_t> clip_span(int32_t offset, uint32_t extent) {
  constexpr int64_t kMax = std::numeric_limits<int32_t>::max();
  const int64_t begin = std::clamp<int64_t>(offset, 0, kMax);
  const int64_t end = std::clamp<int64_t>(int64_t(offset) + int64_t(extent), 0, kMax);
  return {static_cast<int32_t>(begin), static_cast<uint32_t>(std::max<int64_t>(end - begin, 0))};
}

}  // namespace

VkViewport to_vk(const Viewport& viewport) {
  return VkViewport{viewport.x, viewport.y, viewport.width, viewport.height, viewport.min_depth, viewport.max_depth};
}

VkRect2D to_vk_scissor(const Rect2D& scissor) {
  const auto [x, width] = clip_span(scissor.x, scissor.width);
  const auto [y, height] = clip_span(scissor.y, scissor.height);
  return VkRect2D{{x, y}, {width, height}};
}

}  // namespace rastercmp::vk
