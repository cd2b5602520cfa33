#include "cpu_raster/methods/line_dda.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace rastercmp::methods {

namespace {

int32_t round_half_up(double v) { return int32_t(std::floor(v + 0.5)); }

// The notes' loop; `visit(pixel, minor)` per step. Returns the shape (steps left empty).
template <class Visit>
DdaTrace walk_dda(PixelXY p0, PixelXY p1, Visit&& visit) {
  const int64_t dx = int64_t(p1.x) - p0.x, dy = int64_t(p1.y) - p0.y;
  DdaTrace shape;
  shape.steep = std::llabs(dy) > std::llabs(dx);  // |k| > 1: step along y
  const bool steep = shape.steep;
  const int64_t steps = steep ? std::llabs(dy) : std::llabs(dx);
  if (steps == 0) {
    visit(p0, double(steep ? p0.x : p0.y));
    return shape;
  }
  shape.major_step = (steep ? dy : dx) > 0 ? 1 : -1;
  shape.slope = double(steep ? dx : dy) / double(steps);  // minor change per major step
  const double k = shape.slope;
  double minor = steep ? p0.x : p0.y;
  int32_t major = steep ? p0.y : p0.x;
  for (int64_t i = 0; i <= steps; ++i) {
    visit(steep ? PixelXY{round_half_up(minor), major} : PixelXY{major, round_half_up(minor)}, minor);
    major += shape.major_step;
    minor += k;
  }
  return shape;
}

}  // namespace

std::vector<PixelXY> line_dda(PixelXY p0, PixelXY p1) {
  std::vector<PixelXY> pixels;
  pixels.reserve(size_t(std::max(std::llabs(int64_t(p1.x) - p0.x), std::llabs(int64_t(p1.y) - p0.y))) + 1);
  walk_dda(p0, p1, [&](PixelXY pixel, double) { pixels.push_back(pixel); });
  return pixels;
}

DdaTrace line_dda_trace(PixelXY p0, PixelXY p1) {
  std::vector<DdaStep> steps;
  DdaTrace trace = walk_dda(p0, p1, [&](PixelXY pixel, double minor) { steps.push_back({pixel, minor}); });
  trace.steps = std::move(steps);
  return trace;
}

}  // namespace rastercmp::methods
