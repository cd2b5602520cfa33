// What the fill methods produce: horizontal runs of pixels (spans), and the pixel grid they
// address. Pixel (x, y) is the unit cell [x, x+1) x [y, y+1) of the integer grid; where inside it
// is sampled is each fill's own convention, stated in its header.
//
// Does: the value types, expanding spans to pixels or to a coverage callback, merging pixels of a
//       row into spans, per-pixel coverage counts.
// Does not: decide coverage (see fill_*.hpp).
#pragma once

#include <compare>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace rastercmp::methods {

struct PixelXY {
  int32_t x = 0, y = 0;
  friend auto operator<=>(const PixelXY&, const PixelXY&) = default;
};

// Pixels x_begin <= x < x_end of row y.
struct Span {
  int32_t y = 0, x_begin = 0, x_end = 0;
  friend bool operator==(const Span&, const Span&) = default;
};

// Half-open pixel rectangle x_min <= x < x_max, y_min <= y < y_max that a fill may write.
struct PixelBounds {
  int32_t x_min = -(1 << 24), y_min = -(1 << 24), x_max = 1 << 24, y_max = 1 << 24;
};

// ceil(v) as a pixel index, clamped to +-2^30 so far-away geometry cannot overflow.
int32_t ceil_to_pixel(double v);

using CoverageCallback = std::function<void(int32_t x, int32_t y)>;

void for_each_pixel(const std::vector<Span>& spans, const CoverageCallback& covered);

// Row by row, left to right, in span order.
std::vector<PixelXY> spans_to_pixels(const std::vector<Span>& spans);

// Collects spans: add runs of one row at a time (any x order within the row); adjacent or
// overlapping runs of the same row added consecutively are merged.
class SpanBuilder {
 public:
  void add(int32_t y, int32_t x_begin, int32_t x_end);  // ignores empty runs
  std::vector<Span> take() { return std::move(spans_); }

 private:
  std::vector<Span> spans_;
};

// Clamps a run to the bounds' columns (row bounds are the fill's own loop limits).
void add_clamped(SpanBuilder& builder, const PixelBounds& bounds, int32_t y, int32_t x_begin, int32_t x_end);

// How many of `span_sets` cover each pixel of a width x height grid at (0, 0); index y*width + x.
std::vector<uint32_t> coverage_counts(const std::vector<std::vector<Span>>& span_sets, int32_t width, int32_t height);

}  // namespace rastercmp::methods
