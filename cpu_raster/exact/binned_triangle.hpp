// llvmpipe's own integer set-up, binning and tile rasterization of a triangle, with its 32-bit
// wrap-around, for the triangles whose numbers leave the range where "every plane E > 0 at the
// sample" is what llvmpipe computes (docs/lavapipe-rules.md §7.5). Only a clipper fed vertices
// around 1e12 w produces those: its float cancellation leaves new vertices millions of pixels out.
//
// The steps, each a Mesa 22.3.6 function (gallium/drivers/llvmpipe):
//  - calc_fixed_position: cvtps2dq saturates to INT32_MIN; coordinate differences are int32 and wrap;
//  - do_triangle_ccw (SSE branch): dcdx, dcdy int32 differences, c = dcdx*X - dcdy*Y in int64,
//    c += 1 when dcdx < 0 or (dcdx == 0 and dcdy >= 0), then dcdx, dcdy <<= 8 and eo in int32 (wrap);
//    the box x0 = min >> 8, x1 = (max - 1) >> 8 in int32;
//  - lp_setup_bin_triangle: one tile when the box crosses no 64-pixel boundary, otherwise every tile
//    of box ∩ draw region tested in int64 with the wrapped dcdx, dcdy, eo: "out", "whole tile" or
//    "partial" with the planes not trivially accepted, and a row left at its first "out" tile after
//    an "in" one;
//  - lp_rast_tri_tmp.h with RASTER_64 (lp_rast_triangle_N, do_block_16, do_block_4, and their
//    MULTISAMPLE forms): 16x16 and 4x4 blocks judged in int32 from c >> 8, the pixels (or samples)
//    of a partial 4x4 block by the sign of (int32)((c - 1) >> 8) + i*dcdx + j*dcdy.
// Inside the direct range (in_direct_range) this gives exactly the plane test of rasterize.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cpu_raster/exact/draw_region.hpp"
#include "cpu_raster/exact/edge_plane.hpp"
#include "cpu_raster/exact/fixed_point.hpp"
#include "model/lavapipe_release.hpp"

namespace rastercmp::cpu {

// struct lp_rast_plane: c in int64, dcdx and dcdy shifted left by 8 (int32), eo (uint32).
struct LpPlane {
  int64_t c = 0;
  int32_t dcdx = 0, dcdy = 0;
  uint32_t eo = 0;
};

// A triangle (counter-clockwise, llvmpipe's sense) whose coverage follows llvmpipe's binning.
struct BinnedTriangle {
  std::array<LpPlane, 8> plane{};  // 3 edges, then the scissor planes
  uint32_t plane_count = 0;
  bool multisample = false;
  int32_t tiles_x = 0, tiles_y = 0;  // the framebuffer's 64x64 tiles
  // Per tile, row-major: bit 31 set for a whole tile, else the mask of planes binned (0: not binned).
  std::vector<uint32_t> tile_planes;
};

// The doubled area of calc_fixed_position, from int32 differences that wrap.
int64_t wrapped_doubled_area(const std::array<FixedPoint, 3>& v);

// do_triangle_ccw's box, in int32 (max - 1 wraps at INT32_MIN).
PixelRect wrapped_triangle_bbox(const std::array<FixedPoint, 3>& v);

// Whether no step above can overflow, so that the direct plane test is exact: every edge has
// |dcdx| + |dcdy| < 2^23 fixed units (dcdx << 8 and eo fit in int32, and a tile's c >> 8 in int32).
// Inline (with quad_in_direct_range): set-up tests every primitive.
template <size_t N>
inline bool edges_in_direct_range(const std::array<FixedPoint, N>& v) {
  for (size_t i = 0; i < N; ++i) {
    const size_t j = (i + 1) % N;
    const int64_t dx = v[i].x.wide() - v[j].x.wide(), dy = v[i].y.wide() - v[j].y.wide();
    if ((dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy) >= (int64_t(1) << 23)) return false;
  }
  return true;
}
inline bool in_direct_range(const std::array<FixedPoint, 3>& v) { return edges_in_direct_range(v); }

// Mesa 26.2 reworked this arithmetic (dcdx and dcdy no longer shifted, binning in exact int64,
// other wrap points: lavapipe-rules §8.7); the profile does not model it and refuses a primitive
// that needs it (NotSupportedError naming the rule) rather than guess.
void refuse_if_overflow_reworked(const LavapipeRules& rules);

// The three edge planes of do_triangle_ccw for a counter-clockwise triangle.
std::array<LpPlane, 3> lp_edge_planes(const std::array<FixedPoint, 3>& v);

// Lines past the direct range (Mesa 23.2 and later draw lines unclipped in x and y, so their quads
// reach it; rules §8.2): the same test over the quad's four edges, try_setup_line's four planes
// (int32 differences, c in int64, c += 1 when dcdx < 0 or (dcdx == 0 and dcdy > 0), then dcdx,
// dcdy *= 256 in int32 and eo from the shifted values' signs) and its box, x0 = (min + 255) >> 8,
// x1 = ((max + 255) >> 8) - 1, in int32.
inline bool quad_in_direct_range(const std::array<FixedPoint, 4>& corners) { return edges_in_direct_range(corners); }
std::array<LpPlane, 4> lp_line_planes(const std::array<FixedPoint, 4>& corners);
PixelRect wrapped_line_bbox(const std::array<FixedPoint, 4>& corners);

// lp_setup_add_scissor_planes' plane for one of draw_region.hpp's scissor EdgePlanes.
LpPlane lp_scissor_plane(const EdgePlane& scissor);

// lp_setup_bin_triangle for the planes, with the box clamped at 0 and the draw region.
BinnedTriangle bin_triangle(const std::array<LpPlane, 8>& planes, uint32_t plane_count, const PixelRect& bbox,
                            const PixelRect& region, const PixelRect& framebuffer, bool multisample);

// Whether llvmpipe's rasterizer covers the sample (pixel px, py; sample index for 4x, else 0).
bool binned_covers(const BinnedTriangle& t, int32_t px, int32_t py, uint32_t sample);

// The 16 values of one plane over a 4x4 grid of blocks (BUILD_MASKS, build_masks_sse) at one level
// of lp_rast_tri_tmp.h: `shift` 4 for a tile's 16x16 blocks, 2 for a 16x16 block's 4x4 blocks;
// `c` is the plane's value at the grid's corner. Sets bit j*4 + i of `out` when the block's
// trivial-reject value is negative, of `part` when its trivial-accept value is (ORs into both).
void block_masks(const LpPlane& p, int64_t c, int shift, uint32_t& out, uint32_t& part);

// do_block_4's test of pixel (i, j) of a 4x4 block whose plane value at the corner is c
// (BUILD_MASK_LINEAR; per sample with `multisample`).
bool stamp_pixel_passes(const LpPlane& p, int64_t c, int32_t i, int32_t j, bool multisample, uint32_t sample);

}  // namespace rastercmp::cpu
