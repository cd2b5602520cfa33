// Depth plane and depth bias set-up, all float32 with every operation rounded on its own (the
// set-up JIT never emits llvm.fmuladd; the line set-up is C built without FMA).
//  - triangles: lp_state_setup.c calc_coef4 on the post-swap vertices (docs/lavapipe-rules.md §3.2, step 14);
//  - depth bias: lp_do_offset_tri (§4.3, step 15), triangles only — lines get none (§4.4);
//  - lines: lp_setup_line.c linear_coef (§5.5).
// The plane is z(px, py) = a0 + dzdx*px + dzdy*py with px, py the integer pixel coordinates (plus
// the sample offset for multisampling); a0 already holds the -pixel_center shift.
#pragma once

#include <array>

#include "cpu_raster/exact/viewport.hpp"
#include "model/lavapipe_release.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

struct DepthPlane {
  float a0 = 0, dzdx = 0, dzdy = 0;
};

// How the polygon offset o was formed (kept for explain).
struct DepthOffset {
  bool computed = false;    // false: bias off or both factors 0 after conversion, o = 0 exactly (the terms
                            // below are then 0, or formed with zero factors and unused: WorkSkips)
  float m = 0;              // max(|dz/dx|, |dz/dy|)
  float r = 0;              // minimum resolvable difference applied to the constant factor
  float constant_term = 0;  // r * constant factor, as lavapipe forms it
  float unclamped = 0;
  bool clamped = false;
  float offset = 0;  // o, added to every fragment before the [0,1] clamp
};

// pixel_center: 0.5 single sample, 0 multisample (key->multisample).
DepthPlane triangle_depth_plane(const std::array<WindowVertex, 3>& v, float pixel_center);

// How a UNORM format's constant factor c becomes depth units (lp_make_setup_variant_key):
// (float)(c * mrd * 2) in double (§4.3), or from Mesa 25.2 (float)(fl(c ± 0.5f) * mrd) for c != 0
// (§8.4). Float formats take c as it is in both.
enum class UnormBiasUnits { TwiceMrd, HalfUnitRounding };

// skip_when_off: the bias is off or both factors are 0, so o = 0 and no term is formed. false
// (WorkSkips::bias_only_when_enabled off): the terms are formed with zero factors, o stays 0.
DepthOffset triangle_depth_offset(const std::array<WindowVertex, 3>& v, const DepthBias& bias, DepthFormat format,
                                  bool skip_when_off = true, UnormBiasUnits units = UnormBiasUnits::TwiceMrd);

// The release's UnormBiasUnits (model/lavapipe_release.hpp).
inline UnormBiasUnits unorm_bias_units(const LavapipeRules& rules) {
  return rules.has(LavapipeRule::UnormBiasHalfUnit) ? UnormBiasUnits::HalfUnitRounding : UnormBiasUnits::TwiceMrd;
}

// Line plane from the original first/second endpoint; dx_eff/dy_eff are dx, dy for rectangular
// lines and the "wide line" weighted ones for Bresenham lines (§5.5).
DepthPlane line_depth_plane(const WindowVertex& v1, const WindowVertex& v2, float dx_eff, float dy_eff,
                            float one_over_area, float pixel_offset);

}  // namespace rastercmp::cpu
