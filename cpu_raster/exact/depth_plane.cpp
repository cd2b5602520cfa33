#include "cpu_raster/exact/depth_plane.hpp"

#include <cmath>

#include "cpu_raster/exact/float_ops.hpp"
#include "model/depth_format.hpp"

namespace rastercmp::cpu {
namespace {

// 1 / (dx01*dy20 - dy01*dx20), shared by the plane and the offset (init_args).
float one_over_area(const std::array<WindowVertex, 3>& v) {
  const float dx01 = v[0].x - v[1].x, dy01 = v[0].y - v[1].y;
  const float dx20 = v[2].x - v[0].x, dy20 = v[2].y - v[0].y;
  const float e = dx01 * dy20;
  const float f = dy01 * dx20;
  return 1.0f / (e - f);
}

// The UNORM r, lp_make_setup_variant_key: (float)(constant * mrd * 2) in double,
// util_get_depth_format_mrd: mrd = 1 / (2^n - 1) (docs/lavapipe-rules.md §4.3). From Mesa 25.2 the
// constant is first moved half a unit away from 0 in float, and not doubled (§8.4).
float unorm_constant_term(float constant, DepthFormat format, UnormBiasUnits units) {
  const DenormalsKept state_time;  // lp_make_setup_variant_key runs before draw_vbo (rules §7.11)
  const double mrd = depth_format_info(format).mrd;
  if (units == UnormBiasUnits::TwiceMrd) return static_cast<float>(double(constant) * mrd * 2);
  if (constant == 0.0f) return constant;                               // "offset_units != 0"
  const float adjusted = constant + (constant > 0.0f ? 0.5f : -0.5f);  // a float add
  return static_cast<float>(double(adjusted) * mrd);
}

// D32_SFLOAT r = 2^(e - n) from the largest |z| of the vertices, by the exponent-bit trick
// (docs/lavapipe-rules.md §4.3; n = mantissa_bits of the table, 23).
float float_format_r(const std::array<WindowVertex, 3>& v, uint32_t mantissa_bits) {
  float max_z = std::fabs(v[0].z);
  if (std::fabs(v[1].z) > max_z) max_z = std::fabs(v[1].z);
  if (std::fabs(v[2].z) > max_z) max_z = std::fabs(v[2].z);
  int32_t exponent = int32_t(float_bits(max_z) & 0x7f800000u) - int32_t(mantissa_bits << 23);
  if (exponent < 0) exponent = 0;
  return float_from_bits(uint32_t(exponent));
}

}  // namespace

DepthPlane triangle_depth_plane(const std::array<WindowVertex, 3>& v, float pixel_center) {
  const float x0_center = v[0].x - pixel_center;
  const float y0_center = v[0].y - pixel_center;
  const float dx01 = v[0].x - v[1].x, dy01 = v[0].y - v[1].y;
  const float dx20 = v[2].x - v[0].x, dy20 = v[2].y - v[0].y;
  const float ooa = one_over_area(v);
  const float dx20_ooa = dx20 * ooa, dy20_ooa = dy20 * ooa;
  const float dx01_ooa = dx01 * ooa, dy01_ooa = dy01 * ooa;
  const float dz01 = v[0].z - v[1].z;
  const float dz20 = v[2].z - v[0].z;
  DepthPlane plane;
  plane.dzdx = dz01 * dy20_ooa - dz20 * dy01_ooa;  // docs/lavapipe-rules.md §3.2
  plane.dzdy = dz20 * dx01_ooa - dz01 * dx20_ooa;
  plane.a0 = v[0].z - (plane.dzdx * x0_center + plane.dzdy * y0_center);  // at the framebuffer origin
  return plane;
}

DepthOffset triangle_depth_offset(const std::array<WindowVertex, 3>& v, const DepthBias& bias_in, DepthFormat format,
                                  bool skip_when_off, UnormBiasUnits unorm_units) {
  DepthOffset o;
  const DepthFormatInfo info = depth_format_info(format);
  const bool float_depth = info.encoding == DepthEncoding::Float;
  const float units_in =
      float_depth ? bias_in.constant_factor : unorm_constant_term(bias_in.constant_factor, format, unorm_units);
  // The C of lp_make_setup_variant_key and of the set-up's code generation, before draw_vbo: a
  // denormal factor or clamp counts as non-zero there (rules §7.11), and the generated code then
  // reads it as 0 where the set-up runs under DAZ.
  const bool applied = bias_in.enable && !(is_zero_bits(units_in) && is_zero_bits(bias_in.slope_factor));
  if (!applied && skip_when_off) return o;  // o = 0.0f exactly
  // Not applied (the skip is off): the same arithmetic with zero factors; its result is not used.
  const DepthBias bias = applied ? bias_in : DepthBias{false, 0.0f, 0.0f, 0.0f};
  const float units = applied ? units_in : 0.0f;
  const float dx01 = v[0].x - v[1].x, dy01 = v[0].y - v[1].y;
  const float dx20 = v[2].x - v[0].x, dy20 = v[2].y - v[0].y;
  const float dz01 = v[0].z - v[1].z, dz20 = v[2].z - v[0].z;
  const float ooa = one_over_area(v);
  const float res0 = dz20 * dy01 - dy20 * dz01;  // lp_do_offset_tri (§4.3)
  const float res1 = dx20 * dz01 - dz20 * dx01;
  const float dzdx = std::fabs(res0 * ooa);
  const float dzdy = std::fabs(res1 * ooa);
  o.m = unordered_greater(dzdx, dzdy) ? dzdx : dzdy;  // NaN picks dz/dx
  const float mult = o.m * bias.slope_factor;
  if (float_depth) {
    o.r = float_format_r(v, info.mantissa_bits);
    o.constant_term = o.r * units;
  } else {
    o.r = static_cast<float>(depth_format_info(format).mrd * (unorm_units == UnormBiasUnits::TwiceMrd ? 2 : 1));
    o.constant_term = units;
  }
  o.unclamped = o.constant_term + mult;
  o.offset = o.unclamped;
  if (is_positive_bits(bias.clamp))  // key->pgon_offset_clamp > 0, decided in C before draw_vbo
    o.offset = sse_min(bias.clamp, o.offset);
  else if (is_negative_bits(bias.clamp))
    o.offset = sse_max(bias.clamp, o.offset);
  o.clamped = float_bits(o.offset) != float_bits(o.unclamped);
  o.computed = applied;
  if (!applied) o.offset = 0.0f;  // m may be Inf or NaN, so m * 0 need not be 0
  return o;
}

DepthPlane line_depth_plane(const WindowVertex& v1, const WindowVertex& v2, float dx_eff, float dy_eff,
                            float one_over_area, float pixel_offset) {
  const float dz21 = v1.z - v2.z;
  DepthPlane plane;
  plane.dzdx = dz21 * dx_eff * one_over_area;
  plane.dzdy = dz21 * dy_eff * one_over_area;
  plane.a0 = v1.z - (plane.dzdx * (v1.x - pixel_offset) + plane.dzdy * (v1.y - pixel_offset));
  return plane;
}

}  // namespace rastercmp::cpu
