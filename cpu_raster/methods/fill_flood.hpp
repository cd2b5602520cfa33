// Flood fill from a seed, iterative (an explicit stack, no recursion, so a large region cannot
// overflow the call stack). Notes: lecture-rasterization-depth-sorting-culling.txt "Flood Fill"
// (flood_fill(x, y): if read_pixel(x, y) == WHITE { write_pixel(x, y, BLACK); recurse on the
// four neighbours }).
//
// Does: replaces the connected region of cells that hold the seed's value ("WHITE") by
//       `replacement` ("BLACK"), 4-connected as in the notes or 8-connected; cells outside the
//       grid are boundary. Returns the new grid (the input is not changed) and the cell count.
// Does not: scan-convert the boundary first (draw it with line_bresenham.hpp), fill with
//       patterns, or work on geometry — it only sees cell values.
#pragma once

#include <cstdint>
#include <vector>

#include "cpu_raster/methods/spans.hpp"

namespace rastercmp::methods {

// Row-major cells; index y * width + x.
struct CellGrid {
  int32_t width = 0, height = 0;
  std::vector<uint32_t> cells;

  bool contains(PixelXY p) const { return p.x >= 0 && p.y >= 0 && p.x < width && p.y < height; }
  uint32_t at(PixelXY p) const { return cells[size_t(p.y) * size_t(width) + size_t(p.x)]; }
};

enum class Connectivity { Four, Eight };

struct FloodFillResult {
  CellGrid grid;
  uint64_t filled = 0;  // cells changed
};

// A seed outside the grid, or one already holding `replacement`, changes nothing.
// Throws std::invalid_argument if cells.size() != width * height.
FloodFillResult flood_fill(const CellGrid& grid, PixelXY seed, uint32_t replacement,
                           Connectivity connectivity = Connectivity::Four);

}  // namespace rastercmp::methods
