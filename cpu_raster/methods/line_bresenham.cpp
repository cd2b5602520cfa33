#include "cpu_raster/methods/line_bresenham.hpp"

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace rastercmp::methods {

namespace {

// The notes' complete version; `visit(step)` per pixel. Returns the shape (steps left empty).
template <class Visit>
BresenhamTrace walk_bresenham(PixelXY p0, PixelXY p1, Visit&& visit) {
  int64_t x0 = p0.x, y0 = p0.y, x1 = p1.x, y1 = p1.y;
  BresenhamTrace shape;
  shape.steep = std::llabs(y1 - y0) > std::llabs(x1 - x0);
  if (shape.steep) {
    std::swap(x0, y0);
    std::swap(x1, y1);
  }
  shape.swapped = x0 > x1;
  if (shape.swapped) {
    std::swap(x0, x1);
    std::swap(y0, y1);
  }
  const int64_t delta_x = x1 - x0, delta_y = std::llabs(y1 - y0);
  const int64_t y_step = y0 < y1 ? 1 : -1;
  shape.delta_x = delta_x, shape.delta_y = delta_y, shape.y_step = y_step;
  int64_t error = 0, y = y0;
  for (int64_t x = x0; x <= x1; ++x) {
    BresenhamStep step;
    step.pixel = shape.steep ? PixelXY{int32_t(y), int32_t(x)} : PixelXY{int32_t(x), int32_t(y)};
    error += delta_y;
    step.error_added = error;
    step.minor_step = 2 * error >= delta_x;
    if (step.minor_step) {
      y += y_step;
      error -= delta_x;
    }
    step.error_after = error;
    visit(step);
  }
  return shape;
}

}  // namespace

std::vector<PixelXY> line_bresenham(PixelXY p0, PixelXY p1) {
  std::vector<PixelXY> pixels;
  pixels.reserve(size_t(std::max(std::llabs(int64_t(p1.x) - p0.x), std::llabs(int64_t(p1.y) - p0.y))) + 1);
  walk_bresenham(p0, p1, [&](const BresenhamStep& step) { pixels.push_back(step.pixel); });
  return pixels;
}

BresenhamTrace line_bresenham_trace(PixelXY p0, PixelXY p1) {
  std::vector<BresenhamStep> steps;
  BresenhamTrace trace = walk_bresenham(p0, p1, [&](const BresenhamStep& step) { steps.push_back(step); });
  trace.steps = std::move(steps);
  return trace;
}

}  // namespace rastercmp::methods
