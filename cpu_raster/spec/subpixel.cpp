#include "cpu_raster/spec/subpixel.hpp"

#include <cmath>
#include <string>

#include "model/errors.hpp"

namespace rastercmp::cpu::spec {
namespace {

Wide wide_abs(Wide v) { return v < 0 ? -v : v; }

int64_t floor_div(int64_t n, int64_t d) {  // d > 0
  return n >= 0 ? n / d : -((-n + d - 1) / d);
}

int64_t ceil_div(int64_t n, int64_t d) { return -floor_div(-n, d); }

int64_t half_size(uint32_t bits, bool multisample) {
  const int64_t half_pixel = int64_t(1) << (bits - 1);
  return multisample ? half_pixel + kSampleToleranceUnits : kSampleToleranceUnits;
}

}  // namespace

uint32_t effective_sub_pixel_bits(uint32_t requested) {
  if (requested == 0)
    throw UsageError("subPixelPrecisionBits 0: the spec profile needs at least 1 (Vulkan requires at least 4)");
  return requested > kMaxSubPixelBits ? kMaxSubPixelBits : requested;
}

SnapCell snap_cell(double x_window, double y_window, uint32_t bits) {
  const double scale = std::ldexp(1.0, int(bits));  // exact: a power of two
  const double x = x_window * scale, y = y_window * scale;
  return {int64_t(std::floor(x)), int64_t(std::ceil(x)), int64_t(std::floor(y)), int64_t(std::ceil(y))};
}

ToleranceBox pixel_box(int32_t px, int32_t py, uint32_t bits, bool multisample) {
  const int64_t one = int64_t(1) << bits;
  return {px * one + one / 2, py * one + one / 2, half_size(bits, multisample)};
}

double pixel_box_half_px(uint32_t bits, bool multisample) {
  return std::ldexp(double(half_size(bits, multisample)), -int(bits));
}

PixelSpan pixels_touching(int64_t lo, int64_t hi, uint32_t bits, bool multisample) {
  const int64_t one = int64_t(1) << bits, half = half_size(bits, multisample);
  return {ceil_div(lo - one / 2 - half, one), floor_div(hi - one / 2 + half, one)};
}

LineEquation line_through(GridPoint from, GridPoint to) {
  // cross(to - from, p - from) = dx*(y - from.y) - dy*(x - from.x)
  const Wide dx = Wide(to.x) - from.x, dy = Wide(to.y) - from.y;
  return {-dy, dx, dy * from.x - dx * from.y};
}

LineEquation negated(const LineEquation& e) { return {-e.a, -e.b, -e.c}; }

Wide min_over_box(const LineEquation& e, const ToleranceBox& box) {
  return value_at(e, box.cx, box.cy) - Wide(box.half) * (wide_abs(e.a) + wide_abs(e.b));
}

Wide max_over_box(const LineEquation& e, const ToleranceBox& box) {
  return value_at(e, box.cx, box.cy) + Wide(box.half) * (wide_abs(e.a) + wide_abs(e.b));
}

}  // namespace rastercmp::cpu::spec
