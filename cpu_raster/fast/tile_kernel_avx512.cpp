// The tile kernel (tile_kernel.hpp) on AVX-512 hosts, sixteen pixels per step with the uncovered
// columns masked off. Coverage: for jobs at most 32 columns wide from origin_x, each row's edge
// values (narrow16, one or two steps per row); for wider ones, each row's covered columns from the
// edges (row_columns_avx2.hpp, the same code as the AVX2 kernel's). A step has no branch on its
// data: the masked loads and stores touch only covered pixels (so never a pixel outside the
// rectangle, which lies inside the framebuffer), and the depth test is a mask. The
// depth arithmetic is avx512_depth.hpp's: avx2_depth.hpp's operations, one intrinsic each, on
// sixteen lanes.
#include <immintrin.h>

#include "cpu_raster/fast/avx512_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"
#include "cpu_raster/fast/row_columns_avx2.hpp"
#include "cpu_raster/fast/small_triangles.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"

namespace rastercmp::cpu::fast {
namespace {

// The job's plane and the draw's depth state (avx512_depth.hpp's Depth16) in registers: stores to
// the attachments may alias the job and the KernelDepth, whose fields would be reloaded after each
// store otherwise.
struct Plane16 {
  __m512 a0, dzdx, dzdy, offset;
  Depth16 depth;
};

RASTERCMP_AVX512 inline Plane16 plane16(const KernelJob& j, const KernelDepth& d) {
  return Plane16{_mm512_set1_ps(j.a0), _mm512_set1_ps(j.dzdx), _mm512_set1_ps(j.dzdy), _mm512_set1_ps(j.offset),
                 depth16(d)};
}

// span_z (tile_kernel_avx2.cpp) in the same order: fl(FMA?(dzdy, py, FMA?(dzdx, px, a0)) + o),
// then finish_depth16 (min(z, 1), max(z, 0), the depth clamp). The inner FMA depends on the
// columns only: `inner` (column_depth16) is formed once per step's columns where they repeat.
RASTERCMP_AVX512 inline __m512 column_depth16(const Plane16& p, __m512i lane, int32_t x) {
  const __m512 px = _mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(x), lane));  // exact below 2^24
  return mul_add16(p.dzdx, px, p.a0, p.depth.fma);
}
RASTERCMP_AVX512 inline __m512 fragment_depth16(const Plane16& p, __m512 inner, __m512 py) {
  return finish_depth16(_mm512_add_ps(mul_add16(p.dzdy, py, inner, p.depth.fma), p.offset), p.depth);
}

// One step: the depth test and writes of the `covered` pixels of sixteen columns from x in row y
// (inner: column_depth16 of those columns).
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 inline __mmask16 step16(const Plane16& plane, __m512 inner, __m512i owner, uint32_t* owner_row,
                                         uint32_t* depth_row, int32_t x, __m512 py, __mmask16 covered) {
  __mmask16 pass = covered;
  if constexpr (F != DepthFormat::None) {
    const __m512i raw = to_raw16<F>(fragment_depth16(plane, inner, py));
    if constexpr (Op != CompareOp::Always)
      pass = passing<F, Op>(covered, raw, _mm512_maskz_loadu_epi32(covered, depth_row + x));
    if (plane.depth.write) _mm512_mask_storeu_epi32(depth_row + x, pass, raw);
  }
  _mm512_mask_storeu_epi32(owner_row + x, pass, owner);
  return pass;
}

// Jobs at most 32 columns wide from origin_x: per row the edges' G - 1 of one or two steps of
// sixteen columns (32-bit, stepped by gy from row to row: the AVX2 kernel's narrow loop, and
// within tile_edges.hpp's bound: a pixel at most 8 columns past the tile has |G| < 71 * 2^24 < 2^31),
// covered where all three are >= 0 and the column lies in the rectangle. Cheaper than the covered
// columns for a narrow triangle: a few operations per row instead of a division per edge and
// four rows. Each row takes its steps whether or not a pixel is covered (an empty mask loads and
// stores nothing): a branch on the mask cost more in mispredictions than the steps it saved
// (perspective -4%, docs/performance-log.md, 4ada090).
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 bool narrow16(const KernelJob& j, const KernelDepth& d, const TileTarget& t) {
  const Plane16 plane = plane16(j, d);
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i owner = _mm512_set1_epi32(int32_t(j.owner));
  const bool two = j.rect.x1 - j.origin_x >= 16;
  __m512i e[3], gy[3], half[3];
  for (int i = 0; i < 3; ++i) {
    e[i] = _mm512_add_epi32(_mm512_set1_epi32(j.g_minus_1[i]), _mm512_mullo_epi32(lane, _mm512_set1_epi32(j.gx[i])));
    gy[i] = _mm512_set1_epi32(j.gy[i]);
    half[i] = _mm512_set1_epi32(16 * j.gx[i]);
  }
  // both strips masked to the rectangle's columns (a small lane's piece may start right of origin_x + 16)
  const __m512i column = _mm512_add_epi32(_mm512_set1_epi32(j.origin_x), lane);
  const __m512i column2 = _mm512_add_epi32(column, _mm512_set1_epi32(16));
  const __m512i rect_x0 = _mm512_set1_epi32(j.rect.x0), rect_x1 = _mm512_set1_epi32(j.rect.x1);
  const __mmask16 in_rect[2] = {
      __mmask16(_mm512_cmpge_epi32_mask(column, rect_x0) & _mm512_cmple_epi32_mask(column, rect_x1)),
      __mmask16(_mm512_cmpge_epi32_mask(column2, rect_x0) & _mm512_cmple_epi32_mask(column2, rect_x1))};
  // the job's and target's fields in locals: the stores below may alias them (no reload per row)
  const size_t width = size_t(t.width);
  const int32_t x = j.origin_x, y1 = j.rect.y1;
  __m512 inner[2] = {_mm512_setzero_ps(), _mm512_setzero_ps()};
  if constexpr (F != DepthFormat::None) {
    inner[0] = column_depth16(plane, lane, x);
    inner[1] = column_depth16(plane, lane, x + 16);
  }
  uint32_t* owner_row = t.owner + size_t(j.rect.y0) * width;
  uint32_t* depth_row = F != DepthFormat::None ? t.depth + size_t(j.rect.y0) * width : nullptr;
  __mmask16 any = 0;
  for (int32_t y = j.rect.y0; y <= y1; ++y, owner_row += width) {
    const __m512 py = _mm512_set1_ps(float(y));
    const __mmask16 covered =
        in_rect[0] & _mm512_cmpge_epi32_mask(_mm512_ternarylogic_epi32(e[0], e[1], e[2], 0xFE), _mm512_setzero_si512());
    any |= step16<F, Op>(plane, inner[0], owner, owner_row, depth_row, x, py, covered);
    if (two) {
      const __mmask16 right =
          in_rect[1] & _mm512_cmpge_epi32_mask(_mm512_ternarylogic_epi32(_mm512_add_epi32(e[0], half[0]),
                                                                          _mm512_add_epi32(e[1], half[1]),
                                                                          _mm512_add_epi32(e[2], half[2]), 0xFE),
                                               _mm512_setzero_si512());
      any |= step16<F, Op>(plane, inner[1], owner, owner_row, depth_row, x + 16, py, right);
    }
    if constexpr (F != DepthFormat::None) depth_row += width;
    for (int i = 0; i < 3; ++i) e[i] = _mm512_add_epi32(e[i], gy[i]);
  }
  return any != 0;
}

template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 bool kernel16(const KernelJob& j, const KernelDepth& d, const TileTarget& t) {
  if constexpr (Op == CompareOp::Never && F != DepthFormat::None) return false;
  if (j.rect.x1 - j.origin_x < 32) return narrow16<F, Op>(j, d, t);
  const Plane16 plane = plane16(j, d);
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i owner = _mm512_set1_epi32(int32_t(j.owner));
  const size_t width = size_t(t.width);
  __mmask16 any = 0;
  CoveredRows rows;
  init_covered_rows(rows, j);
  int32_t y, x, x_end;
  while (rows.next(y, x, x_end)) {
    const __m512 py = _mm512_set1_ps(float(y));
    uint32_t* const owner_row = t.owner + size_t(y) * width;
    uint32_t* const depth_row = F != DepthFormat::None ? t.depth + size_t(y) * width : nullptr;
    for (; x <= x_end; x += 16) {
      const uint32_t left = uint32_t(x_end - x + 1);
      const __mmask16 columns = __mmask16(left >= 16 ? 0xFFFFu : (1u << left) - 1u);
      const __m512 inner = F != DepthFormat::None ? column_depth16(plane, lane, x) : _mm512_setzero_ps();
      any |= step16<F, Op>(plane, inner, owner, owner_row, depth_row, x, py, columns);
    }
  }
  return any != 0;
}

// A kernel job of a small-triangle block (small_triangles.hpp): the same kernel on the lane's job.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 bool small_kernel16(const SmallBlockOutput& b, int lane, uint32_t owner, int32_t row_lo,
                                     int32_t row_hi, const KernelDepth& d, const TileTarget& t) {
  return kernel16<F, Op>(b.job(lane, owner, Op, row_lo, row_hi), d, t);
}

// The same over a piece of the lane's rectangle: the job's edges and depth are the lane's (from
// its origin), its rectangle the piece, to which kernel16 masks every store.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 bool small_piece16(const SmallBlockOutput& b, int lane, uint32_t owner, const PixelRect& piece,
                                    const KernelDepth& d, const TileTarget& t) {
  KernelJob j = b.job(lane, owner, Op, piece.y0, piece.y1);
  j.rect.x0 = piece.x0;
  j.rect.x1 = piece.x1;
  return kernel16<F, Op>(j, d, t);
}

struct SmallKernels {
  template <DepthFormat F, CompareOp Op>
  static constexpr SmallKernelFn get() {
    return &small_kernel16<F, Op>;
  }
};
constexpr auto kSmallKernels = kernel_table<SmallKernels>();

struct SmallPieces {
  template <DepthFormat F, CompareOp Op>
  static constexpr SmallPieceFn get() {
    return &small_piece16<F, Op>;
  }
};
constexpr auto kSmallPieces = kernel_table<SmallPieces>();

struct Kernels {
  template <DepthFormat F, CompareOp Op>
  static constexpr KernelFn get() {
    return &kernel16<F, Op>;
  }
};
constexpr auto kKernels = kernel_table<Kernels>();  // [format][op] (format_dispatch.hpp)

}  // namespace

KernelFn select_kernel_avx512(DepthFormat format, CompareOp op) { return select_kernel(kKernels, format, op); }

SmallKernelFn select_small_kernel_avx512(DepthFormat format, CompareOp op) {
  return select_kernel(kSmallKernels, format, op);
}

SmallPieceFn select_small_piece_avx512(DepthFormat format, CompareOp op) {
  return select_kernel(kSmallPieces, format, op);
}

}  // namespace rastercmp::cpu::fast
