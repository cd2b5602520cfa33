#include "cpu_raster/exact/depth_sample.hpp"

#include <cmath>

#include "cpu_raster/exact/float_ops.hpp"
#include "model/depth_format.hpp"

namespace rastercmp::cpu {

float interpolate_depth(const DepthPlane& plane, float px, float py, bool fma) {
  return mul_add(plane.dzdy, py, mul_add(plane.dzdx, px, plane.a0, fma), fma);  // lp_bld_interp.c
}

SampleDepth sample_depth(const DepthPlane& plane, float offset, float px, float py, const DepthRange& range,
                         DepthFormat format, bool fma) {
  SampleDepth d;
  d.interpolated = interpolate_depth(plane, px, py, fma);
  d.with_offset = d.interpolated + offset;                     // a separate fadd, always issued
  d.clamped_01 = sse_max(sse_min(d.with_offset, 1.0f), 0.0f);  // lp_build_clamp: min, then max
  d.depth_clamped = range.clamp ? sse_max(sse_min(d.clamped_01, range.zmax), range.zmin) : d.clamped_01;
  d.raw = depth_to_raw(format, d.depth_clamped);
  return d;
}

// docs/lavapipe-rules.md §3.5, by the conversion the depth-format table names.
uint32_t depth_to_raw(DepthFormat format, float z) {
  const DepthFormatInfo info = depth_format_info(format);
  switch (info.conversion) {
    case DepthConversion::MagicNumber: {
      const float scaled = z * magic_scale(info);                    // D16: 65535/65536, exact in float
      return float_bits(scaled + magic_bias(info)) & info.raw_mask;  // the magic-number trick (D16: + 128)
    }
    case DepthConversion::ScaleRound:
      return static_cast<uint32_t>(std::nearbyint(z * float(unorm_max(info))));  // cvtps2dq
    case DepthConversion::FloatBits: return float_bits(z);
    case DepthConversion::None: break;
  }
  return 0;
}

uint32_t clear_depth_raw(DepthFormat format, float clear_value) {
  const double z = clear_value;
  const DepthFormatInfo info = depth_format_info(format);
  switch (info.encoding) {
    case DepthEncoding::Unorm:
      if (z <= 0.0) return 0;
      if (z >= 1.0) return unorm_max(info);
      return static_cast<uint32_t>(std::lrint(z * unorm_max(info)));
    case DepthEncoding::Float: return float_bits(clear_value);
    case DepthEncoding::None: break;
  }
  return 0;
}


}  // namespace rastercmp::cpu
