// 24.8 fixed-point window coordinates (lavapipe FIXED_ORDER = 8, docs/lavapipe-rules.md §2.2) and
// the two snapping rules lavapipe uses: SSE cvtps2dq for triangle vertices, util_iround for lines.
#pragma once

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

// Triangle vertex snapping, lp_setup_tri.c calc_fixed_position (rules §2.2, step 9):
// X = round(fl(fl(x_window - pixel_offset) * 256)). nullopt: NaN or beyond the bound.
std::optional<Fixed24_8> snap_vertex(float x_window, float pixel_offset, SnapRounding rounding);

// The same rounding as cvtps2dq returns it: NaN and values outside int32 become INT32_MIN
// (0x80000000), which llvmpipe then uses as a coordinate (binned_triangle.hpp, rules §7.5).
int32_t snap_vertex_saturating(float x_window, float pixel_offset, SnapRounding rounding);

// Mesa util_iround on x86-64 without x87: (int)(f + 0.5f) for f >= 0, (int)(f - 0.5f) otherwise;
// the add is a float operation, then the value is truncated (rules §5.3).
std::optional<int32_t> util_iround(float value);

// lp_setup_line.c subpixel_snap(a) = util_iround(256 * a), in fixed units.
std::optional<int32_t> line_snap(float value_pixels);

}  // namespace rastercmp::cpu
