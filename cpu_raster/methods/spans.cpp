#include "cpu_raster/methods/spans.hpp"

#include <algorithm>
#include <cmath>

namespace rastercmp::methods {

int32_t ceil_to_pixel(double v) {
  constexpr double kLimit = double(1 << 30);
  return int32_t(std::clamp(std::ceil(v), -kLimit, kLimit));
}

void for_each_pixel(const std::vector<Span>& spans, const CoverageCallback& covered) {
  for (const Span& span : spans) {
    for (int32_t x = span.x_begin; x < span.x_end; ++x) covered(x, span.y);
  }
}

std::vector<PixelXY> spans_to_pixels(const std::vector<Span>& spans) {
  std::vector<PixelXY> pixels;
  for_each_pixel(spans, [&](int32_t x, int32_t y) { pixels.push_back({x, y}); });
  return pixels;
}

void SpanBuilder::add(int32_t y, int32_t x_begin, int32_t x_end) {
  if (x_begin >= x_end) return;
  if (!spans_.empty()) {
    Span& last = spans_.back();
    if (last.y == y && x_begin <= last.x_end && x_end >= last.x_begin) {
      last.x_begin = std::min(last.x_begin, x_begin);
      last.x_end = std::max(last.x_end, x_end);
      return;
    }
  }
  spans_.push_back({y, x_begin, x_end});
}

void add_clamped(SpanBuilder& builder, const PixelBounds& bounds, int32_t y, int32_t x_begin, int32_t x_end) {
  builder.add(y, std::max(x_begin, bounds.x_min), std::min(x_end, bounds.x_max));
}

std::vector<uint32_t> coverage_counts(const std::vector<std::vector<Span>>& span_sets, int32_t width, int32_t height) {
  std::vector<uint32_t> counts(size_t(std::max(width, 0)) * size_t(std::max(height, 0)), 0);
  for (const std::vector<Span>& spans : span_sets) {
    for_each_pixel(spans, [&](int32_t x, int32_t y) {
      if (x >= 0 && x < width && y >= 0 && y < height) ++counts[size_t(y) * size_t(width) + size_t(x)];
    });
  }
  return counts;
}

}  // namespace rastercmp::methods
