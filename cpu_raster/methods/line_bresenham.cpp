#include "cpu_raster/methods/line_bresenham.hpp"

#include <cstdlib>
#include <utility>

namespace rastercmp::methods {

std::vector<PixelXY> line_bresenham(PixelXY p0, PixelXY p1) {
  int64_t x0 = p0.x, y0 = p0.y, x1 = p1.x, y1 = p1.y;
  const bool steep = std::llabs(y1 - y0) > std::llabs(x1 - x0);
  if (steep) {
    std::swap(x0, y0);
    std::swap(x1, y1);
  }
  if (x0 > x1) {
    std::swap(x0, x1);
    std::swap(y0, y1);
  }
  const int64_t delta_x = x1 - x0, delta_y = std::llabs(y1 - y0);
  const int64_t y_step = y0 < y1 ? 1 : -1;
  int64_t error = 0, y = y0;
  std::vector<PixelXY> pixels;
  pixels.reserve(size_t(delta_x) + 1);
  for (int64_t x = x0; x <= x1; ++x) {
    pixels.push_back(steep ? PixelXY{int32_t(y), int32_t(x)} : PixelXY{int32_t(x), int32_t(y)});
    error += delta_y;
    if (2 * error >= delta_x) {
      y += y_step;
      error -= delta_x;
    }
  }
  return pixels;
}

}  // namespace rastercmp::methods
