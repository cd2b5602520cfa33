// Depth of one sample, from the plane to the stored bits, and the depth test
// (docs/lavapipe-rules.md §3.3-§3.6, steps 16-17):
//   z = fl(FMA?(dzdy, py, FMA?(dzdx, px, a0)) + o)
//   z = max(min(z, 1), 0)                      (always: VK_EXT_depth_range_unrestricted is off)
//   z = max(min(z, zmax), zmin)                (depth clamp only)
//   D16: bits(fl(fl(z*(65535/65536)) + 128)) & 0xFFFF;  D24: rne(fl(z*16777215));  D32: z
#pragma once

#include <cmath>
#include <cstdint>

#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "model/depth_format.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

// `a op b` with ordered comparisons (false for NaN operands except Always and NotEqual), the
// compare ops of "Depth Comparison" on any ordered type.
template <class T>
bool ordered_compare(CompareOp op, T a, T b) {
  switch (op) {
    case CompareOp::Never: return false;
    case CompareOp::Less: return a < b;
    case CompareOp::Equal: return a == b;
    case CompareOp::LessOrEqual: return a <= b;
    case CompareOp::Greater: return a > b;
    case CompareOp::NotEqual: return a != b;
    case CompareOp::GreaterOrEqual: return a >= b;
    case CompareOp::Always: return true;
  }
  return false;
}

// Every intermediate value, for explain; `raw` is what the attachment stores.
struct SampleDepth {
  float interpolated = 0;  // before the offset
  float with_offset = 0;
  float clamped_01 = 0;
  float depth_clamped = 0;  // equals clamped_01 when depth clamp is off
  uint32_t raw = 0;
};

// What the draw's depth state adds to the plane (ranges from the viewport, §3.4).
struct DepthRange {
  bool clamp = false;
  float zmin = 0, zmax = 1;
};

// px, py: pixel coordinates as floats, plus the sample offset for multisampling.
float interpolate_depth(const DepthPlane& plane, float px, float py, bool fma);

SampleDepth sample_depth(const DepthPlane& plane, float offset, float px, float py, const DepthRange& range,
                         DepthFormat format, bool fma);

// lp_bld_conv.c lp_build_clamped_float_to_unsigned_norm, or the float bits for D32 (§3.5).
uint32_t depth_to_raw(DepthFormat format, float z);

// The clear value as llvmpipe packs it (util_pack_z: lrint in double; D32: the float bits).
uint32_t clear_depth_raw(DepthFormat format, float clear_value);

// LLVM's unordered predicates (ULT, UEQ, ...): true whenever an operand is NaN.
inline bool unordered_compare(CompareOp op, float a, float b) {
  if (op == CompareOp::Never) return false;
  if (std::isnan(a) || std::isnan(b)) return true;
  return ordered_compare(op, a, b);
}

// The depth test: unsigned compare for UNORM formats, unordered IEEE compare for D32 (§3.6).
// Inline: the fast path's exact rows call it per sample.
inline bool depth_test_passes(CompareOp op, DepthFormat format, uint32_t fragment_raw, uint32_t stored_raw) {
  if (is_float(format))  // docs/lavapipe-rules.md §3.6
    return unordered_compare(op, float_from_bits(fragment_raw), float_from_bits(stored_raw));
  return ordered_compare(op, fragment_raw, stored_raw);
}

}  // namespace rastercmp::cpu
