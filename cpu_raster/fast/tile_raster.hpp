// One triangle over one rectangle of one tile: edge set-up (tile_edges.hpp), the tile's depth
// bounds (tile_depth_bounds.hpp), then the AVX2 kernel or its scalar twin, which evaluates each
// pixel with the exact path's own functions (edge_value, sample_depth, depth_test_passes).
#pragma once

#include <algorithm>
#include <cstdint>

#include "cpu_raster/exact/rasterize.hpp"
#include "cpu_raster/fast/fast_triangle.hpp"
#include "cpu_raster/fast/small_triangles.hpp"
#include "cpu_raster/fast/small_window.hpp"
#include "cpu_raster/fast/tile_depth_bounds.hpp"
#include "cpu_raster/fast/tile_edges.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"

namespace rastercmp::cpu::fast {

// What rasterizing a draw needs.
struct DrawRaster {
  DepthTestState depth;          // the exact path's (cpu::make_depth_test_state)
  KernelDepth kernel;            // the same, for the AVX2 kernels
  bool vector_ok = true;         // the AVX2 kernels reproduce this state (UNORM depth stays below 2^24)
  bool bounds = false;           // tile depth bounds are used and kept for this draw
  SmallKernelFn small_fn = nullptr;
  // AVX-512 hosts: small_fn over a piece of a lane's rectangle, writing nothing outside it (null
  // elsewhere: the AVX2 kernel stores back whole spans, up to kJobLead columns left of a lane).
  SmallPieceFn small_piece_fn = nullptr;
  GridScatterFn grid_fn = nullptr;
  GridBlockFn grid_block_fn = nullptr;
  WindowBlockFn window_block_fn = nullptr;  // with avx2: 8 or 16 pixels a step (small_window.hpp)
};

// Shared by the workers of a frame; a tile (and its bounds) is only touched by the worker that
// owns it (TileState::worker), so nothing here needs a lock.
struct FrameRaster {
  TileTarget target;
  int32_t tiles_x = 0, tiles_y = 0;
  TileState* tiles = nullptr;  // tiles_x * tiles_y, row-major
  bool avx2 = false;
  bool avx512 = false;  // the tile kernel sixteen pixels per step (tile_kernel_avx512.cpp)
  SmallSetupFn small_setup = nullptr;           // the eight-wide set-up for this host (AVX2 hosts)
  SmallPairSetupFn small_pair_setup = nullptr;  // the sixteen-wide one (AVX-512 hosts)
  bool bounds = false;                          // depth bounds usable in this frame (tile_depth_bounds.hpp)
  uint32_t depth_clear_raw = 0;                 // clear_depth_raw of the scene's clear value

  TileState& tile(int32_t tile_x, int32_t tile_y) const {
    return tiles[size_t(tile_y) * size_t(tiles_x) + size_t(tile_x)];
  }
};

// avx2: the AVX2 kernels and the eight-pixel window compositor; avx512 (which implies avx2):
// their AVX-512 builds and the sixteen-pixel compositor.
DrawRaster make_draw_raster(const DepthTestState& depth, bool frame_bounds, bool avx2, bool avx512);

// What raster_in_tile computes first for a triangle and a rectangle of a tile: the kernel job's
// edges (none: no sample of r in the triangle) and, with depth bounds, its fragments' range.
struct TileTriangle {
  KernelJob job;  // job.rect: the rectangle
  EdgeSetup edges;
  FragmentRange fragment;
  bool ranged = false;  // fragment holds the range

  // Every pixel of the tile covered.
  bool covers(const PixelRect& whole_tile) const { return edges.all_in && job.rect == whole_tile; }
};
// range_small: the range also for rectangles below the area the bounds are used at.
TileTriangle prepare_in_tile(const FastTriangle& t, const PixelRect& r, const DrawRaster& draw, bool range_small);

// What the depth bounds did for one call: not consulted, or the verdict they gave (PerPixel: no
// help; AllPass and AllFail: the test, or the whole job, left out). BandWorker's audit counts them.
enum class BoundsUse { None, PerPixel, Helped };

// Rectangle r lies inside tile (tile_x, tile_y) and inside the triangle's rect.
BoundsUse raster_in_tile(const FastTriangle& t, const PixelRect& r, int32_t tile_x, int32_t tile_y,
                         const DrawRaster& draw, const FrameRaster& frame);
BoundsUse raster_prepared(const FastTriangle& t, const TileTriangle& prepared, int32_t tile_x, int32_t tile_y,
                          const DrawRaster& draw, const FrameRaster& frame);

// Before the first write into a tile of row tile_y, and for the rows no primitive reached: the
// clear values (kOwnerBackground, the packed depth clear) written into every tile of the row that
// `worker` draws (TileState::worker) and that is not cleared yet, which are then marked cleared. A
// tile that a later triangle would have covered whole is cleared all the same (its clear is no
// longer skipped, raster_prepared).
void clear_tile_row(int32_t tile_y, uint32_t worker, const FrameRaster& frame);
// The same for every pixel of r (whole tiles): one fill per attachment and pixel row, or one for
// all of r when its rows span the whole width.
void clear_rect(const PixelRect& r, const FrameRaster& frame);

// p[0, count) = value: `rep stosl` for runs of 4096 words and more, 32-byte stores below
// (tile_kernel_avx2.cpp).
// Call only when host_has_avx2_fma().
void fill_words_avx2(uint32_t* p, size_t count, uint32_t value);

// The scalar kernel: the exact path's per-pixel functions; returns whether any pixel was written.
bool raster_scalar(const FastTriangle& t, const PixelRect& r, const DepthTestState& depth, const TileTarget& target);

// intersect (draw_region.hpp) inline, for the per-tile loops over a batch (an out-of-line call
// there cost about 2.5% of perspective's instructions).
inline PixelRect rect_in_tile(const PixelRect& r, const PixelRect& tile) {
  return PixelRect{std::max(r.x0, tile.x0), std::max(r.y0, tile.y0), std::min(r.x1, tile.x1), std::min(r.y1, tile.y1)};
}

// Pixel rectangle of a tile, clipped to the framebuffer.
inline PixelRect tile_rect(int32_t tile_x, int32_t tile_y, const TileTarget& target) {
  return PixelRect{tile_x * kTileSize, tile_y * kTileSize, std::min(tile_x * kTileSize + kTileSize, target.width) - 1,
                   std::min(tile_y * kTileSize + kTileSize, target.height) - 1};
}

}  // namespace rastercmp::cpu::fast
