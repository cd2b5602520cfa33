// What a renderer hands back: per-sample owner ids and raw stored depth bits.
// Layout of both arrays: index = (y * width + x) * samples + sample.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/pixel_buffer.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Owner of a sample: which draw and which primitive of it wrote the sample last.
inline constexpr uint32_t kOwnerBackground = 0xFFFFFFFFu;
inline constexpr uint32_t encode_owner(uint32_t draw, uint32_t primitive) {
  return (draw << 24) | (primitive & 0x00FFFFFFu);
}
inline constexpr uint32_t owner_draw(uint32_t owner) { return owner >> 24; }
inline constexpr uint32_t owner_primitive(uint32_t owner) { return owner & 0x00FFFFFFu; }

// Per-pixel classification of the spec profile (three states of the CTS verifier).
enum class CoverageClass : uint8_t { MustNot = 0, May = 1, Must = 2 };

// Spec profile: which widening of a depth interval dominated one of its bounds
// (docs/spec-profile.md "Depth intervals").
enum class DepthTerm : uint8_t { Plane, Snapping, Bias, Precision, Rounding, Clear, Undefined };
const char* to_string(DepthTerm);

// Spec profile: the raw stored depth values any conformant device may leave at a sample,
// inclusive, ordered as depth values (depth_raw_order). `any`: the specification leaves the value
// undefined there, every value is allowed.
struct DepthInterval {
  uint32_t lo_raw = 0, hi_raw = 0;
  DepthTerm lo_term = DepthTerm::Plane, hi_term = DepthTerm::Plane;
  bool any = false;
  bool operator==(const DepthInterval&) const = default;
};

// The device limits the spec profile may read, as a capture's render.json records them ("limits").
// A capture without them is judged as any conformant device could have made it: these defaults are
// the specification's minimum guarantees ("Limit Requirements": subPixelPrecisionBits 4,
// viewportSubPixelBits 0, strictLines and standardSampleLocations not required, lineWidthRange
// (1.0, 1.0)).
struct DeviceLimits {
  uint32_t sub_pixel_precision_bits = 4;
  uint32_t viewport_sub_pixel_bits = 0;
  bool strict_lines = false;
  bool standard_sample_locations = false;
  float line_width_min = 1.0f, line_width_max = 1.0f;
  bool operator==(const DeviceLimits&) const = default;
};

// Spec profile: an owner other than RenderResult::owner[sample] that a device computing the
// specification's equations exactly, with other choices the specification leaves to it (vertex
// rounding, tie rule, r and m of depth bias, D32 rounding), leaves at a Must sample
// (cpu_raster/spec/exact_owners.hpp, docs/spec-profile.md "Owners").
struct OwnerAlternative {
  uint64_t sample = 0;
  uint32_t owner = 0;
  bool operator==(const OwnerAlternative&) const = default;
};
struct RenderResult {
  std::string backend;  // "cpu" or "vulkan"
  std::string device;   // device or profile description
  // Vulkan only: the device's name and driver apart, and its limits (absent in older captures).
  std::string device_name, driver;
  std::optional<DeviceLimits> limits;
  bool fma = false;  // whether the depth/viewport arithmetic was fused
  uint32_t width = 0, height = 0, samples = 1;
  DepthFormat depth_format = DepthFormat::None;
  PixelBuffer owner;      // width*height*samples
  PixelBuffer depth_raw;  // same size, or empty when depth was not produced
  // Spec profile only: per-sample must / may / must-not coverage of the union of all draws.
  std::vector<CoverageClass> coverage_class;
  // Spec profile only: per-sample interval of allowed stored depth (empty without depth).
  std::vector<DepthInterval> depth_interval;
  // Spec profile only: sorted by sample, then owner; empty where no sample has one.
  std::vector<OwnerAlternative> owner_alternatives;

  size_t index(uint32_t x, uint32_t y, uint32_t sample = 0) const { return (size_t(y) * width + x) * samples + sample; }
  bool has_depth() const { return !depth_raw.empty(); }
};

// Raw stored bits → depth value in [0,1] (UNORM k/(2^n-1), D32 reinterpreted).
double depth_raw_to_value(DepthFormat, uint32_t raw);

// A key ordered like the depth values the raw bits stand for: the UNORM integer, or for float
// formats the float bits mapped so that integer order is float order (+0 and -0 both 0) and the
// distance counts the representable floats in between.
int64_t depth_raw_order(DepthFormat, uint32_t raw);

// Whether `owner` is one of the owner alternatives of sample `index` (binary search).
bool is_owner_alternative(const RenderResult&, size_t index, uint32_t owner);

// Whether `raw` lies in the interval (always, when it is `any`).
bool depth_in_interval(DepthFormat, const DepthInterval&, uint32_t raw);

}  // namespace rastercmp
