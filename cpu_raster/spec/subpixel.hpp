// The sub-pixel grid of the device being judged, and the tolerance box around a sample, in the
// integer units of that grid (1 unit = 2^-bits pixel). This is the frame in which the CTS
// rasterization verifier (tcuRasterizationVerifier calculateTriangleCoverage in the Vulkan CTS,
// docs/spec-profile.md) decides FULL / PARTIAL / NONE:
//  - a vertex snaps to the grid with an unspecified rounding (Vulkan "Controlling the Viewport":
//    x_f, y_f keep subPixelPrecisionBits fractional bits), so each coordinate is either its floor
//    or its ceiling on the grid: a vertex lies somewhere in its SnapCell;
//  - a single-sample sample is judged through a box of ±3 units around the pixel centre ("3
//    subpixel tolerance to account for accumulated errors"); a multisample pixel through its
//    whole square, every sample alike (sample positions need not be the standard ones).
#pragma once

#include <cstdint>

namespace rastercmp::cpu::spec {

// Edge values need more than 64 bits: coordinates reach 2^31 units (|x| <= 32768 px at 16 bits,
// viewportBoundsRange), coordinate differences 2^32, products 2^64.
using Wide = __int128;

// The CTS clamps subpixelBits to 16. Judging a finer device on the 16-bit grid is still sound:
// a value rounded on a finer grid lies between its floor and ceiling on the coarser one.
inline constexpr uint32_t kMaxSubPixelBits = 16;
// CTS single-sample tolerance, grid units either side of the pixel centre.
inline constexpr int64_t kSampleToleranceUnits = 3;
// Window coordinates beyond this many pixels cannot come out of clipping (viewportBoundsRange
// ±32768 plus float slack); a vertex there is treated as undefined.
inline constexpr double kMaxWindowMagnitude = 65536.0;

// `requested` clamped to kMaxSubPixelBits. Throws UsageError for 0 (Vulkan requires >= 4).
uint32_t effective_sub_pixel_bits(uint32_t requested);

struct GridPoint {
  int64_t x = 0, y = 0;
};

// Floor and ceiling of a window position on the grid: where a conformant device can snap it.
struct SnapCell {
  int64_t x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0;
  // Corner k: bit 0 picks x_hi, bit 1 picks y_hi.
  GridPoint corner(int k) const { return {(k & 1) ? x_hi : x_lo, (k & 2) ? y_hi : y_lo}; }
  SnapCell widened(int64_t units) const { return {x_lo - units, x_hi + units, y_lo - units, y_hi + units}; }
};

// Needs |x|, |y| <= kMaxWindowMagnitude (finite).
SnapCell snap_cell(double x_window, double y_window, uint32_t bits);

// Axis-aligned square of half-size `half` around (cx, cy), grid units.
struct ToleranceBox {
  int64_t cx = 0, cy = 0, half = 0;
};

// The box that stands for pixel (px, py): ±3 units around its centre (single sample), or the
// pixel square grown by the same 3 units (multisample; the CTS takes the bare square, the margin
// keeps samples placed right at the pixel border inside the box).
ToleranceBox pixel_box(int32_t px, int32_t py, uint32_t bits, bool multisample);

// That box's half-size in pixels.
double pixel_box_half_px(uint32_t bits, bool multisample);

// Pixels [first, last] along one axis whose boxes can touch the grid interval [lo, hi].
struct PixelSpan {
  int64_t first = 0, last = -1;
};
PixelSpan pixels_touching(int64_t lo, int64_t hi, uint32_t bits, bool multisample);

// E(p) = a*x + b*y + c over grid points.
struct LineEquation {
  Wide a = 0, b = 0, c = 0;
};

// cross(to - from, p - from): positive left of from→to in a frame where y points up
// (right of it on the y-down framebuffer).
LineEquation line_through(GridPoint from, GridPoint to);
LineEquation negated(const LineEquation& e);

inline Wide value_at(const LineEquation& e, int64_t x, int64_t y) { return e.a * x + e.b * y + e.c; }

// Smallest / largest value of E over the box: at the centre ∓ half * (|a| + |b|).
Wide min_over_box(const LineEquation& e, const ToleranceBox& box);
Wide max_over_box(const LineEquation& e, const ToleranceBox& box);

}  // namespace rastercmp::cpu::spec
