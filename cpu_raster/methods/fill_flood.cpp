#include "cpu_raster/methods/fill_flood.hpp"

#include <stdexcept>

namespace rastercmp::methods {

FloodFillResult flood_fill(const CellGrid& grid, PixelXY seed, uint32_t replacement, Connectivity connectivity) {
  if (grid.width < 0 || grid.height < 0 || grid.cells.size() != size_t(grid.width) * size_t(grid.height)) {
    throw std::invalid_argument("flood_fill: cells.size() must equal width * height");
  }
  FloodFillResult result{grid, 0};
  if (!grid.contains(seed) || grid.at(seed) == replacement) return result;
  const uint32_t target = grid.at(seed);  // the notes' WHITE
  // The notes' order of the recursive calls: (x-1, y), (x+1, y), (x, y+1), (x, y-1).
  static constexpr PixelXY kFour[] = {{-1, 0}, {1, 0}, {0, 1}, {0, -1}};
  static constexpr PixelXY kDiagonal[] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
  std::vector<PixelXY> stack{seed};
  while (!stack.empty()) {
    const PixelXY p = stack.back();
    stack.pop_back();
    if (!grid.contains(p)) continue;
    uint32_t& cell = result.grid.cells[size_t(p.y) * size_t(grid.width) + size_t(p.x)];
    if (cell != target) continue;
    cell = replacement;  // write_pixel(x, y, BLACK)
    ++result.filled;
    for (const PixelXY& d : kFour) stack.push_back({p.x + d.x, p.y + d.y});
    if (connectivity == Connectivity::Eight) {
      for (const PixelXY& d : kDiagonal) stack.push_back({p.x + d.x, p.y + d.y});
    }
  }
  return result;
}

}  // namespace rastercmp::methods
