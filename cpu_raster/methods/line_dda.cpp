#include "cpu_raster/methods/line_dda.hpp"

#include <cmath>
#include <cstdlib>

namespace rastercmp::methods {

namespace {

int32_t round_half_up(double v) { return int32_t(std::floor(v + 0.5)); }

}  // namespace

std::vector<PixelXY> line_dda(PixelXY p0, PixelXY p1) {
  const int64_t dx = int64_t(p1.x) - p0.x, dy = int64_t(p1.y) - p0.y;
  const bool steep = std::llabs(dy) > std::llabs(dx);  // |k| > 1: step along y
  const int64_t steps = steep ? std::llabs(dy) : std::llabs(dx);
  std::vector<PixelXY> pixels;
  pixels.reserve(size_t(steps) + 1);
  if (steps == 0) {
    pixels.push_back(p0);
    return pixels;
  }
  const int32_t major_step = (steep ? dy : dx) > 0 ? 1 : -1;
  const double k = double(steep ? dx : dy) / double(steps);  // minor change per major step
  double minor = steep ? p0.x : p0.y;
  int32_t major = steep ? p0.y : p0.x;
  for (int64_t i = 0; i <= steps; ++i) {
    pixels.push_back(steep ? PixelXY{round_half_up(minor), major} : PixelXY{major, round_half_up(minor)});
    major += major_step;
    minor += k;
  }
  return pixels;
}

}  // namespace rastercmp::methods
