// The depth-format table: the one place that knows a depth format's bits (docs/depth-formats.md).
// Every module reads a format's facts from depth_format_info(); the Vulkan format of each entry
// lives in vk_reference/vk_translate.cpp (model/ does not see Vulkan headers).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "model/scene.hpp"

namespace rastercmp {

// How the stored bits encode a depth value.
enum class DepthEncoding { None, Unorm, Float };

// How lavapipe turns a clamped float z into the stored bits (docs/lavapipe-rules.md §3.5).
enum class DepthConversion {
  None,
  MagicNumber,  // fewer bits than the 23-bit mantissa: bits(fl(fl(z * (2^n-1)/2^n) + 2^(23-n))) & mask
  ScaleRound,   // mantissa + 1 bits: cvtps2dq(fl(z * (2^n - 1))), nearest even
  FloatBits,    // float formats: the float's bits unchanged
};

struct DepthFormatInfo {
  DepthFormat format = DepthFormat::None;
  const char* name = "none";  // the scene format's spelling (docs/scene-format.md)
  uint32_t bits = 0;          // bits of the stored depth value
  DepthEncoding encoding = DepthEncoding::None;
  DepthConversion conversion = DepthConversion::None;
  uint32_t raw_mask = 0;         // the raw bits that carry depth (X8 padding excluded)
  uint32_t bytes_per_texel = 0;  // bytes of one texel in a buffer copy of the depth aspect
  // Minimum resolvable difference (util_get_depth_format_mrd): UNORM 1/(2^n - 1) in double; 0 for
  // float formats, whose r depends on the primitive's z (float_depth_r). docs/lavapipe-rules.md §4.3
  double mrd = 0.0;
  uint32_t mantissa_bits = 0;  // float formats: the n of r = 2^(e - n) (docs/lavapipe-rules.md §4.1)
};

namespace depth_format_detail {

constexpr DepthFormatInfo unorm(DepthFormat format, const char* name, uint32_t bits, DepthConversion conversion,
                                uint32_t bytes_per_texel) {
  const uint32_t max_value = uint32_t((uint64_t(1) << bits) - 1);
  return {format, name, bits, DepthEncoding::Unorm, conversion, max_value, bytes_per_texel, 1.0 / double(max_value), 0};
}

constexpr DepthFormatInfo float32(DepthFormat format, const char* name, uint32_t bytes_per_texel) {
  return {format, name, 32, DepthEncoding::Float, DepthConversion::FloatBits, 0xFFFFFFFFu, bytes_per_texel, 0.0, 23};
}

}  // namespace depth_format_detail

// The table. No default: a depth format without an entry does not compile (-Wswitch, -Werror).
constexpr DepthFormatInfo depth_format_info(DepthFormat format) {
  using namespace depth_format_detail;
  switch (format) {
    case DepthFormat::None: return DepthFormatInfo{};
    case DepthFormat::D16Unorm: return unorm(format, "d16_unorm", 16, DepthConversion::MagicNumber, 2);
    case DepthFormat::X8D24Unorm: return unorm(format, "x8_d24_unorm", 24, DepthConversion::ScaleRound, 4);
    case DepthFormat::D32Sfloat: return float32(format, "d32_sfloat", 4);
  }
  return DepthFormatInfo{};
}

// Every enum value in enum order (index == underlying value), None first. The fast path instantiates
// its kernels for each (cpu_raster/fast/format_dispatch.hpp); a new format goes here and in the switch.
inline constexpr std::array<DepthFormat, 4> kAllDepthFormats = {DepthFormat::None, DepthFormat::D16Unorm,
                                                                DepthFormat::X8D24Unorm, DepthFormat::D32Sfloat};

// The formats that store depth, in enum order.
inline constexpr auto kDepthFormats = [] {
  std::array<DepthFormat, kAllDepthFormats.size() - 1> formats{};
  for (size_t i = 1; i < kAllDepthFormats.size(); ++i) formats[i - 1] = kAllDepthFormats[i];
  return formats;
}();

constexpr bool depth_format_list_consistent() {
  for (size_t i = 0; i < kAllDepthFormats.size(); ++i) {
    const DepthFormatInfo info = depth_format_info(kAllDepthFormats[i]);
    if (size_t(kAllDepthFormats[i]) != i || info.format != kAllDepthFormats[i]) return false;
    if ((i == 0) != (info.encoding == DepthEncoding::None)) return false;
  }
  return true;
}
static_assert(depth_format_list_consistent(), "kAllDepthFormats: every DepthFormat once, in enum order");

constexpr bool is_unorm(DepthFormat format) { return depth_format_info(format).encoding == DepthEncoding::Unorm; }
constexpr bool is_float(DepthFormat format) { return depth_format_info(format).encoding == DepthEncoding::Float; }

// The largest UNORM value, 2^n - 1, as the raw integer (= raw_mask for UNORM formats).
constexpr uint32_t unorm_max(const DepthFormatInfo& info) { return info.raw_mask; }

// DepthConversion::MagicNumber's constants (docs/lavapipe-rules.md §3.5): the scale (2^n - 1)/2^n
// and the bias 2^(23 - n), both exact in float (65535/65536 and 128 for D16).
constexpr float magic_scale(const DepthFormatInfo& info) {
  return float(double(unorm_max(info)) / double(uint64_t(unorm_max(info)) + 1));
}
constexpr float magic_bias(const DepthFormatInfo& info) { return float(uint32_t(1) << (23 - info.bits)); }
static_assert(magic_scale(depth_format_info(DepthFormat::D16Unorm)) == 0.9999847412109375f);
static_assert(magic_bias(depth_format_info(DepthFormat::D16Unorm)) == 128.0f);

// Float formats, the spec's r = 2^(e - n) (docs/lavapipe-rules.md §4.1): e the unbiased exponent of
// max_abs_z (-126 at least, and for 0, inf and NaN), n = mantissa_bits. In double, exact.
inline double float_depth_r(const DepthFormatInfo& info, double max_abs_z) {
  int exponent_frexp = 0;
  std::frexp(max_abs_z, &exponent_frexp);  // max_abs_z = m * 2^E, m in [0.5, 1): e = E - 1
  const int e = (max_abs_z == 0.0 || !std::isfinite(max_abs_z)) ? -126 : std::max(exponent_frexp - 1, -126);
  return std::ldexp(1.0, e - int(info.mantissa_bits));
}

}  // namespace rastercmp
