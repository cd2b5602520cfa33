// The fast path's triangle after set-up: what the tile kernels need, in 64 bytes.
// Produced by BandWorker::triangle (unclipped triangles), by setup_piece (clipped pieces) or from
// the exact path's RasterPrimitive; either way the numbers are the exact path's
// (docs/lavapipe-rules.md §2.2-§4.3).
#pragma once

#include <cstdint>

#include "cpu_raster/exact/draw_region.hpp"

namespace rastercmp::cpu::fast {

struct FastTriangle {
  // Post-swap vertices in the snapped 24.8 frame (llvmpipe's counter-clockwise order, §2.3).
  int32_t x_fixed[3] = {0, 0, 0};
  int32_t y_fixed[3] = {0, 0, 0};
  // Pixels that can be covered: bounding box ∩ draw region (single sample, §2.5); never empty.
  PixelRect rect;
  // Depth plane z = FMA?(dzdy, py, FMA?(dzdx, px, a0)) and polygon offset (§3.2, §4.3).
  float a0 = 0, dzdx = 0, dzdy = 0, offset = 0;
  uint32_t owner = 0;
};

// Tiles are 64x64 pixels (llvmpipe's TILE_SIZE); each tile belongs to one worker (TileState::worker).
inline constexpr int32_t kTileOrder = 6;
inline constexpr int32_t kTileSize = 1 << kTileOrder;

}  // namespace rastercmp::cpu::fast
