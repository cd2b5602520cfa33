// The window compositor for blocks of small triangles: a block of grid lanes whose union fits
// kWindowWidth x kWindowHeight pixels (SmallBlockOutput::window) is drawn by loading that window
// of the attachments once, then, lane by lane in primitive order, evaluating the lane's rows 16
// pixels at a time on AVX-512 hosts, 8 on AVX2 hosts (coverage from the 32-bit edge values, raw
// depth from the plane, the depth test against the window) and merging the passing pixels into the
// window with masked moves or blends; the window is stored back once.
//
// Why it is exact: each pixel still sees the block's triangles one by one in primitive order, with
// the exact path's operations (the per-pixel formula of tile_kernel.hpp, the compare of
// depth_test_passes); a pixel outside a lane's bounding box is never covered by it (the box
// holds every sample inside the triangle, and the window lies in the draw region), so no column
// mask is needed but the window's own. What it saves over the lane-by-lane scatter
// (small_triangles.cpp): one load and one store per window row instead of a load, a compare and
// two stores per covered pixel, and no loop end per lane and pixel to predict.
#pragma once

#include "cpu_raster/fast/small_triangles.hpp"

namespace rastercmp::cpu::fast {

// Draws a window block (lane l owned by owner_of_lane_0 + l) into rows [row_lo, row_hi] of t,
// which lie within the block's union and belong to the caller (the other rows are another
// worker's); the rows in between are loaded and stored back whole.
using WindowBlockFn = void (*)(const SmallBlockOutput&, uint32_t owner_of_lane_0, int32_t row_lo, int32_t row_hi,
                               const KernelDepth&, const TileTarget&);

// Call only when host_has_avx512().
WindowBlockFn select_window_block_avx512(DepthFormat format, CompareOp op);
// Call only when host_has_avx2_fma().
WindowBlockFn select_window_block_avx2(DepthFormat format, CompareOp op);

}  // namespace rastercmp::cpu::fast
