// 24.8 fixed-point window coordinates (lavapipe FIXED_ORDER = 8, docs/lavapipe-rules.md §2.2) and
// the two snapping rules lavapipe uses: SSE cvtps2dq for triangle vertices, util_iround for lines.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace rastercmp::cpu {

inline constexpr int kFixedOrder = 8;
inline constexpr int32_t kFixedOne = 1 << kFixedOrder;  // 1 pixel = 256 fixed units

// A window coordinate in 1/256 pixel. The frame is shifted by the set-up's pixel offset, so that
// a sample of pixel (px, py) sits at (256*px + sx, 256*py + sy) with sx, sy the in-pixel sample
// offset (0 for single sampling, docs/lavapipe-rules.md §2.2, §6).
struct Fixed24_8 {
  int32_t raw = 0;

  // Overflow bound. Clipping is exact in x/y (rules §1.4), so window coordinates lie in the
  // viewport: |x| <= 32768 + 16384 px (viewportBoundsRange, maxViewportDimensions) = 49152 px
  // < 2^24 fixed units; line quads add at most half of the largest width, 128 px. Set-up drops a
  // primitive whose coordinates exceed kMaxMagnitude, which only non-finite or out-of-range input
  // reaches (lavapipe turns those into 0x80000000 and its result is undefined, rules §7.6).
  static constexpr int64_t kMaxMagnitude = int64_t(1) << 25;

  static std::optional<Fixed24_8> from_wide(int64_t value) {
    if (value > kMaxMagnitude || value < -kMaxMagnitude) return std::nullopt;
    return Fixed24_8{static_cast<int32_t>(value)};
  }
  int64_t wide() const { return raw; }
};

// Largest sample position, in fixed units: the framebuffer is at most 16384 px.
inline constexpr int64_t kMaxSampleFixed = int64_t(16384 + 1) << kFixedOrder;

// Edge coefficients are coordinate differences (< 2^26); the edge constant c = dcdx*X - dcdy*Y,
// the doubled area and the edge value at a sample c + dcdy*Ys - dcdx*Xs all fit in int64.
inline constexpr int64_t kMaxEdgeDelta = 2 * Fixed24_8::kMaxMagnitude;
static_assert(kMaxEdgeDelta * Fixed24_8::kMaxMagnitude * 2 + 1 <= std::numeric_limits<int64_t>::max() / 4,
              "24.8 edge constants must fit in int64 with room to spare");
static_assert(2 * kMaxEdgeDelta * kMaxSampleFixed <= std::numeric_limits<int64_t>::max() / 4,
              "edge values at a sample must fit in int64");

struct FixedPoint {
  Fixed24_8 x, y;
};

// How the set-up rounds fl(fl(x - offset) * 256) to an integer (the "snap" method stage).
enum class SnapRounding {
  NearestEven,       // lavapipe on x86-64: cvtps2dq under MXCSR round-to-nearest-even (§2.2)
  HalfAwayFromZero,  // ablation "round_half_away": the non-SSE util_iround rule
};

// v rounded to an integer, ties to even: what cvtps2dq gives under MXCSR's default rounding and
// std::nearbyint in the default rounding mode, without libm's call (nearbyintf saves and restores
// the floating-point environment: it was 16% of a scene of 255 one-triangle draws). Below 2^23
// the float addition of 2^23 rounds |v| to an integer (the spacing of floats there is 1, and 2^23
// is even, so a tie goes to the even integer) and the subtraction is exact; from 2^23 on every
// float is an integer, and NaN and Inf come back unchanged. Zero and values below 0.5 keep their
// sign (copysign), as nearbyint's do.
inline float round_nearest_even(float v) {
  constexpr float kTwo23 = 8388608.0f;
  const float magnitude = std::fabs(v);
  if (!(magnitude < kTwo23)) return v;
  return std::copysign((magnitude + kTwo23) - kTwo23, v);
}

// An integral float as int32 when the set-up bound accepts it (|v| <= kMaxMagnitude), else nullopt
// (NaN too).
inline std::optional<int32_t> bounded_int32(float integral_value) {
  if (!(std::fabs(integral_value) <= float(Fixed24_8::kMaxMagnitude))) return std::nullopt;
  return static_cast<int32_t>(integral_value);
}

// fl(fl(x - offset) * 256), rounded to an integral float.
inline float snapped_float(float x_window, float pixel_offset, SnapRounding rounding) {
  const float shifted = x_window - pixel_offset;    // a float subtraction first (§2.2)
  const float scaled = shifted * float(kFixedOne);  // exact: a power of two
  return rounding == SnapRounding::NearestEven ? round_nearest_even(scaled)
                                               : std::round(scaled);  // or half away from zero
}

// Triangle vertex snapping, lp_setup_tri.c calc_fixed_position (rules §2.2, step 9):
// X = round(fl(fl(x_window - pixel_offset) * 256)). nullopt: NaN or beyond the bound. Inline: a
// set-up snaps six times, and an optional returned through memory cost a stalled reload.
inline std::optional<Fixed24_8> snap_vertex(float x_window, float pixel_offset, SnapRounding rounding) {
  const float rounded = snapped_float(x_window, pixel_offset, rounding);
  const std::optional<int32_t> raw = bounded_int32(rounded);
  if (!raw) return std::nullopt;
  return Fixed24_8{*raw};
}

// The same rounding as cvtps2dq returns it: NaN and values outside int32 become INT32_MIN
// (0x80000000), which llvmpipe then uses as a coordinate (binned_triangle.hpp, rules §7.5).
int32_t snap_vertex_saturating(float x_window, float pixel_offset, SnapRounding rounding);

// Mesa util_iround on x86-64 without x87: (int)(f + 0.5f) for f >= 0, (int)(f - 0.5f) otherwise;
// the add is a float operation, then the value is truncated (rules §5.3).
std::optional<int32_t> util_iround(float value);

// lp_setup_line.c subpixel_snap(a) = util_iround(256 * a), in fixed units.
std::optional<int32_t> line_snap(float value_pixels);

// Mesa 23.1 and later: util_iround is (int)lrintf(f) (rules §8.1): f rounded to the nearest
// integer, ties to even, as a 64-bit cvtss2si, then its low 32 bits. NaN, Inf and |f| >= 2^63 give
// 0x8000000000000000, whose low 32 bits are 0. Defined for every float.
int32_t util_iround_lrintf(float value);

// subpixel_snap with that util_iround: the low 32 bits of rne(fl(256 * a)).
int32_t line_snap_lrintf(float value_pixels);

}  // namespace rastercmp::cpu
