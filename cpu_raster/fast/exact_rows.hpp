// The exact rasterizer for the primitives the fast path leaves to it (lines, multisampled
// frames): rasterize_primitive's per-sample evaluation (evaluate_sample), visiting in each row and
// for each sample only the columns whose sample passes every plane, worked out from the planes
// (each E = c + dcdy*Ys - dcdx*Xs is linear in the column, so the passing columns of one plane are
// an interval, and so are those of all of them). The columns it leaves out are the ones the exact
// rasterizer finds uncovered, so the bytes are the same; a line's box, mostly empty, is no longer
// visited whole.
#pragma once

#include "cpu_raster/exact/rasterize.hpp"

namespace rastercmp::cpu::fast {

// Columns [x0, x1] narrowed to those whose sample point (px * kFixedOne + sample_x, y_fixed)
// gives `plane` a value > 0; false when none is left.
bool plane_columns(const EdgePlane& plane, int64_t sample_x, int64_t y_fixed, int32_t& x0, int32_t& x1);

// Same writes as rasterize_primitive(p, depth, targets). avx2 (host_has_avx2_fma()): with an
// active depth test, the raw depths of each sample row eight columns at a time.
void rasterize_primitive_rows(const RasterPrimitive& p, const DepthTestState& depth, RenderTargets& targets,
                              bool avx2);

// Same writes as rasterize_primitive(p, depth, targets) for the rows [y0, y1] of p.visit
// (exact_rows_avx2.cpp; call only when host_has_avx2_fma()): every plane's columns of four sample
// rows per step, then the covered samples' depths, tests and writes eight at a time, gathered from
// any row. False, having written nothing, for a binned primitive, the depth skip off, or planes
// whose values leave the range it evaluates exactly in double: then rasterize_primitive_rows.
// A frame of one sample per pixel's gathered steps write their passing lanes with scatters when
// avx512_writes (call so only on AVX-512 hosts), otherwise every valid lane, a failing one with
// the values it held; its pairs and contiguous steps may also store back, unchanged, pixels of the
// visit that the primitive does not cover. Nothing outside the visit is written, so the visit must
// be pixels no other thread writes during the call (a worker's tiles). With owned_row_end >= 0,
// every column [0, owned_row_end] of the rows [y0, y1] must be the caller's (a worker's whole tile
// rows; owned_row_end at most the frame's last column) and its steps may also store back pixels of
// those columns beside the visit unchanged (fewer gathered and masked steps at a visit's last
// columns); nothing outside them is written.
bool rasterize_rows_avx2(const RasterPrimitive& p, int32_t y0, int32_t y1, const DepthTestState& depth,
                         RenderTargets& targets, bool avx512_writes = false, int32_t owned_row_end = -1);

// The visits of small per-sample primitives in 4x frames that the box kernels take (at most
// kBoxColumns columns and kBoxPixels pixels; exact_rows_4x_avx2.cpp, exact_rows_avx512.cpp).
inline constexpr int32_t kBoxColumns = 24, kBoxPixels = 256;

// One plane of a box kernel: n = E - 1 at the corner of pixel (start, y0), its step per pixel (gx =
// -dcdx * 256) and per row (gy = dcdy * 256). True when every value the kernel forms over the
// columns [start, start + reach_x), each plus a sample's offset (below 256 fixed units each way),
// and the rows [y0, y0 + reach_y) lies in int32: |n| <= |corner| + |gx| * reach_x + |gy| * reach_y
// < 2^31, checked in int64 (then also |dcdx| * 256, |dcdy| * 256 < 2^31).
struct BoxPlane {
  int64_t corner = 0, gx = 0, gy = 0;
};
inline bool box_plane(const EdgePlane& plane, int32_t start, int32_t y0, int64_t reach_x, int64_t reach_y,
                      BoxPlane& out) {
  out.gx = -plane.dcdx * kFixedOne;
  out.gy = plane.dcdy * kFixedOne;
  out.corner = edge_value(plane, int64_t(start) * kFixedOne, int64_t(y0) * kFixedOne) - 1;
  const auto magnitude = [](int64_t v) { return v < 0 ? -v : v; };
  return magnitude(out.corner) + magnitude(out.gx) * reach_x + magnitude(out.gy) * reach_y < (int64_t(1) << 31);
}

// Same writes as rasterize_primitive(p, depth, targets) for the rows [y0, y1] of p.visit, for a
// small per-sample primitive in a 4x frame with an active depth test (exact_rows_avx512.cpp; call
// only on AVX-512 hosts): the box kernel sixteen lanes wide. False, having written nothing, for
// any other primitive or planes whose values leave int32: then rasterize_rows_avx2.
bool rasterize_box_avx512(const RasterPrimitive& p, int32_t y0, int32_t y1, const DepthTestState& depth,
                          RenderTargets& targets);

// Same writes as rasterize_primitive(p, depth, targets) for a binned primitive (p.binned): coverage
// a 64x64 tile at a time from its bins, binned_covers only in partial tiles. avx2: as for
// rasterize_primitive_rows, each run of covered columns of a sample row with its raw depths eight
// columns at a time.
void rasterize_binned_rows(const RasterPrimitive& p, const DepthTestState& depth, RenderTargets& targets, bool avx2);

}  // namespace rastercmp::cpu::fast
