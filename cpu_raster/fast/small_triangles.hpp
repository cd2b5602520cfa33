// Set-up of small triangles eight at a time (AVX2), for meshes whose triangles cover a few
// pixels: per lane the same integer and float operations as the scalar set-up
// (BandWorker::triangle, docs/lavapipe-rules.md §2.2-§3.2). Then, by size:
//  - "grid" lanes (rectangle at most kGridSide x kGridSide pixels, possibly across tile borders:
//    the writes are per pixel): coverage and raw depth of
//    every candidate pixel are computed for the eight triangles at once (triangles in lanes, one
//    pixel position per step); the depth test and the writes are then done triangle by triangle,
//    in order, by scatter_grid_lane;
//  - other small lanes (at most kSmallWidth x kSmallHeight, possibly across tile borders: the
//    rows are cut to the worker's): one kernel call with edge values relative to the triangle's
//    own corner (the 256-scaled E of edge_plane.hpp), one to eight 8-pixel spans per row;
//  - the rest (larger, clipped, non-finite) goes back to the scalar set-up.
//
// 32-bit bound: a small lane's unclipped bounding box spans at most kSmallWidth x kSmallHeight
// pixels, so |X_i - X_j| <= 256*(kSmallWidth + 1) < 2^15 and |Y_i - Y_j| <= 256*(kSmallHeight + 1)
// < 2^14; the doubled area is below 2^29, and an edge value formed within 72 columns (the
// kernel's spans start at x0 or in x1's tile and end in x1's tile, at most 7 columns past x1) and
// kSmallHeight + 4 rows of the corner below 2^14 * 2^15 + 2^15 * 2^14 = 2^30.
#pragma once

#include <cstdint>

#include "cpu_raster/exact/draw_region.hpp"
#include "cpu_raster/fast/fast_triangle.hpp"
#include "cpu_raster/fast/fast_vertices.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::fast {

inline constexpr int32_t kSmallWidth = 64;     // pixels: at most eight 8-lane spans per row
inline constexpr int32_t kSmallHeight = 32;    // rows
inline constexpr int32_t kGridSide = 8;        // candidate pixels per side of a grid lane
inline constexpr int32_t kSmallGridShift = 2;  // blocks whose grid lanes all fit in 4x4 pixels
inline constexpr int32_t kSmallGridSide = 1 << kSmallGridShift;
inline constexpr int32_t kWindowWidth = 32;  // window blocks: two 16-pixel strips per row
inline constexpr int32_t kWindowHeight = 16;

struct SmallBlockInput {
  const FastVertex* vertices = nullptr;
  // Vertex (position) numbers of lane l's corners, already through the index buffer:
  // corners[k][l * stride] (an indexed list's own index buffer, or `copied`).
  const uint32_t* corners[3] = {nullptr, nullptr, nullptr};
  uint32_t stride = 1;
  uint32_t copied[3][8];  // strips, fans, non-indexed draws and a list's last block
  uint32_t* corners_copy(int k) { return copied[k]; }
  uint32_t count = 0;  // lanes in use (the others repeat a valid primitive)
  PixelRect region;
  bool front_ccw = true;
  CullMode cull = CullMode::None;
  KernelDepth depth;       // format None: no depth test
  bool window_ok = false;  // blocks may be left to the window compositor (small_window.hpp)
};

struct SmallBlockOutput {
  uint32_t scalar_mask = 0;  // lanes for the scalar set-up
  uint32_t job_mask = 0;     // lanes for a per-triangle kernel call
  uint32_t grid_mask = 0;    // lanes whose pixels are in grid_bits / grid_raw
  alignas(32) int32_t x0[8], y0[8], x1[8], y1[8], origin_x[8];
  alignas(32) int32_t g_minus_1[3][8], gx[3][8], gy[3][8];
  alignas(32) float a0[8], dzdx[8], dzdy[8];
  // Grid lanes: with side = 1 << grid_shift (kSmallGridSide when every grid lane's rectangle fits
  // in it, else kGridSide), bit p = dy*side + dx is set when pixel (x0 + dx, y0 + dy) is covered;
  // its raw depth is grid_raw[p][lane] (only the block's window is written). With the small side,
  // grid_words[w] also holds lanes 4w..4w+3's bits, 16 per lane (scatter_block's single loop).
  int32_t grid_shift = 3;
  int32_t grid_x0 = 0, grid_y0 = 0, grid_x1 = -1, grid_y1 = -1;  // the union of the grid lanes' rectangles
  alignas(32) uint64_t grid_bits[8];
  uint64_t grid_words[2];
  alignas(32) uint32_t grid_raw[kGridSide * kGridSide][8];
  // A window block (small_window.hpp): grid lanes only, their union at most
  // kWindowWidth x kWindowHeight; grid_bits and grid_raw are not filled, the compositor evaluates
  // each lane from e_window (E - 1 at column grid_x0 of the lane's first row y0), gx, gy and the
  // plane (a0, dzdx, dzdy).
  bool window = false;
  alignas(32) int32_t e_window[3][8];

  // The lane's job in rows [row_lo, row_hi] of its rectangle (offset 0: draws with depth bias take
  // the scalar set-up).
  KernelJob job(int lane, uint32_t owner, CompareOp op, int32_t row_lo, int32_t row_hi) const;

  // A job lane's edge i, E - 1, at pixel (x, y) of its rectangle's columns and rows (the 32-bit
  // bound above holds there): moved from (origin_x, y0) by whole columns and rows.
  int32_t edge_minus_1(int lane, int i, int32_t x, int32_t y) const {
    return g_minus_1[i][lane] + (x - origin_x[lane]) * gx[i][lane] + (y - y0[lane]) * gy[i][lane];
  }
};

// A block in the 4x4 layout goes to the window when its union holds at least this many pixels
// (about 4 per lane): below it, the packed scatter costs less (docs/performance-log.md: d95728d,
// a8e02a1).
inline constexpr int32_t kWindowMinUnion = 32;

// Whether a set-up block goes to the window compositor (small_window.hpp): grid lanes only, their
// union within kWindowWidth x kWindowHeight, and in the 4x4 layout (`shift` is the block's own)
// only when the union holds kWindowMinUnion pixels: pixel-sized lanes keep the packed scatter.
inline bool goes_to_window(const SmallBlockOutput& out, int shift) {
  const int32_t columns = out.grid_x1 - out.grid_x0 + 1, rows = out.grid_y1 - out.grid_y0 + 1;
  return (shift != kSmallGridShift || columns * rows >= kWindowMinUnion) && (out.job_mask | out.scalar_mask) == 0 &&
         columns <= kWindowWidth && rows <= kWindowHeight;
}

// The eight-wide set-up (small_setup_simd.inl), for AVX2 hosts and for AVX-512 hosts.
using SmallSetupFn = void (*)(const SmallBlockInput& in, SmallBlockOutput& out);
void setup_small_block_avx2(const SmallBlockInput& in, SmallBlockOutput& out);
void setup_small_block_avx512(const SmallBlockInput& in, SmallBlockOutput& out);

// The depth planes of eight triangles (corner k of lane l: vertices[corners[k][l]]), as
// triangle_depth_plane forms them, for the MXCSR flags their arithmetic raises (the trailing-run
// check, render_fast.cpp): each lane's flags are the scalar loop's for its triangle in either
// corner order. AVX2 hosts (small_setup_simd.inl). Returns the ORed sign bits of the results.
uint32_t trailing_depth_planes_avx2(const FastVertex* vertices, const uint32_t (&corners)[3][8]);

// The sixteen-wide set-up (small_pair_avx512.cpp, AVX-512 hosts): two blocks of one draw at once
// (in1's corners and count are its own, the draw state is in0's). Each output describes what
// setup_small_block_avx512 gives for its block: the same lane classes, rectangles, covered pixels
// and raw depths, jobs and windows; its grid_shift may be the wider layout of the two blocks'.
using SmallPairSetupFn = void (*)(const SmallBlockInput& in0, const SmallBlockInput& in1, SmallBlockOutput& out0,
                                  SmallBlockOutput& out1);
void setup_small_pair_avx512(const SmallBlockInput& in0, const SmallBlockInput& in1, SmallBlockOutput& out0,
                             SmallBlockOutput& out1);

struct SmallBlock {
  uint32_t first = 0;  // first primitive of the block
  SmallBlockInput in;
  SmallBlockOutput out;
};

// Depth test and writes of one grid lane's pixels in rows [row_lo, row_hi], in raster order;
// returns whether any pixel was written.
using GridScatterFn = bool (*)(const SmallBlockOutput&, int lane, uint32_t owner, int32_t row_lo, int32_t row_hi,
                               bool depth_write, const TileTarget&);
GridScatterFn select_grid_scatter(DepthFormat format, CompareOp op);

// Every grid lane of a block (lane l owned by owner_of_lane_0 + l), all rows.
using GridBlockFn = bool (*)(const SmallBlockOutput&, uint32_t owner_of_lane_0, bool depth_write, const TileTarget&);
GridBlockFn select_grid_block(DepthFormat format, CompareOp op);

}  // namespace rastercmp::cpu::fast
