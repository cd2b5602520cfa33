// The innermost loop of the fast path: one triangle over a rectangle of one tile, 8 pixels of a
// row per step (AVX2), with coverage from 32-bit edge values and depth per pixel from the exact
// formula (docs/lavapipe-rules.md §3.3-§3.6):
//   z = fl(FMA?(dzdy, py, FMA?(dzdx, px, a0)) + o), clamped to [0,1] (and zmin..zmax), converted,
//   compared against the stored value, then depth (when writes are on) and owner written.
// Never incremental depth stepping: every pixel evaluates the plane itself.
#pragma once

#include <cstdint>

#include "cpu_raster/exact/draw_region.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::fast {

// The attachments, single sample, row-major.
struct TileTarget {
  uint32_t* owner = nullptr;
  uint32_t* depth = nullptr;  // null without a depth attachment
  int32_t width = 0, height = 0;
  int32_t samples = 1;  // values per pixel, contiguous (the kernels draw frames of one sample)
};

// A draw's depth state as the kernels use it; format None: no depth test (and no depth writes).
struct KernelDepth {
  DepthFormat format = DepthFormat::None;
  CompareOp op = CompareOp::Always;
  bool write = false;
  bool clamp = false;  // depth clamp to [zmin, zmax] after the [0,1] clamp
  float zmin = 0, zmax = 1;
  bool fma = true;
};

// Coverage of one edge in a tile, in "G" form (tile_edges.hpp): a pixel is covered iff G > 0, and
// G(x, y) = g + gx*(x - origin_x) + gy*(y - origin_y). Stored as G - 1 so the test is a sign bit.
struct KernelJob {
  PixelRect rect;        // pixels to visit: in one tile (or a small lane) and the framebuffer
  int32_t origin_x = 0;  // a tile job's rect.x0 rounded down to 8 (a small lane's: its set-up); origin_y = rect.y0
  int32_t g_minus_1[3] = {0, 0, 0};
  int32_t gx[3] = {0, 0, 0}, gy[3] = {0, 0, 0};
  float a0 = 0, dzdx = 0, dzdy = 0, offset = 0;
  uint32_t owner = 0;
  CompareOp op = CompareOp::Always;  // the draw's op, or Always once hi-z proved that all pass
  bool all_in = false;               // every pixel of rect is covered (the edge fields are unused)
};

// Returns whether any pixel passed (and was written).
using KernelFn = bool (*)(const KernelJob&, const KernelDepth&, const TileTarget&);

struct SmallBlockOutput;
// The kernel for one lane of a block of small triangles (small_triangles.hpp), in rows
// [row_lo, row_hi] of its rectangle (the worker's).
using SmallKernelFn = bool (*)(const SmallBlockOutput&, int lane, uint32_t owner, int32_t row_lo, int32_t row_hi,
                               const KernelDepth&, const TileTarget&);
SmallKernelFn select_small_kernel_avx2(DepthFormat format, CompareOp op);

// The covered columns [x0[k], x1[k]] of row rect.y0 + k of a job as the AVX2 kernel finds them for
// rectangles wider than one span (row_columns_avx2.hpp); x0[k] > x1[k]: none. For tests.
void covered_columns_avx2(const KernelJob& job, int32_t* x0, int32_t* x1);

// One row of samples of a primitive the exact rows draw (exact_rows.cpp): its depth plane and
// polygon offset, the sample's x offset in the pixel and its y (float(py) + the sample's y offset).
struct SampleRowDepth {
  float a0 = 0, dzdx = 0, dzdy = 0, offset = 0;
  float sx = 0, y = 0;
};

// raw[k], k < count rounded up to a multiple of 8 (raw holds that many): the raw depth the exact
// path's sample_depth gives at x = float(x0 + k) + row.sx, y = row.y, with d's format (not None),
// clamp and fma. Call only when host_has_avx2_fma().
void sample_depths_avx2(const SampleRowDepth& row, const KernelDepth& d, int32_t x0, int32_t count, uint32_t* raw);

// The AVX2 kernel for a depth format (None: coverage only) and compare op. Call only when
// host_has_avx2_fma().
KernelFn select_kernel_avx2(DepthFormat format, CompareOp op);

// The same kernel sixteen pixels per step (tile_kernel_avx512.cpp): the same pixels written with
// the same values. Call only when host_has_avx512().
KernelFn select_kernel_avx512(DepthFormat format, CompareOp op);
SmallKernelFn select_small_kernel_avx512(DepthFormat format, CompareOp op);
// The AVX-512 small kernel over `piece`, a rectangle within the lane's (its rows and columns):
// the lane's pixels there, and no other pixel written (every store is masked to the covered,
// passing pixels of the job's rectangle). Lets a lane that crosses into another worker's tile be
// drawn tile by tile.
using SmallPieceFn = bool (*)(const SmallBlockOutput&, int lane, uint32_t owner, const PixelRect& piece,
                              const KernelDepth&, const TileTarget&);
SmallPieceFn select_small_piece_avx512(DepthFormat format, CompareOp op);

}  // namespace rastercmp::cpu::fast
