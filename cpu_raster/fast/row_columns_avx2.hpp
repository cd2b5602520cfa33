// The covered columns of each row of a kernel job, worked out from its edges (row_spans in
// tile_kernel_avx2.cpp; include only from code compiled for AVX2). In the "G" form (tile_edges.hpp)
// edge i covers the pixel at column offset u = x - origin_x of a row iff n_i + gx_i * u >= 0, with
// n_i its G - 1 at origin_x in that row: the covered columns of one edge are an interval, bounded
// below when gx_i > 0 (L = ceil(-n_i / gx_i)) and above when gx_i < 0 (U = floor(-n_i / gx_i)), and
// those of the triangle are their intersection. An edge with gx_i = 0 covers whole rows or none:
// its rows are cut once per job (flat_edge_rows); all-in edges (0, 0, 0) cover everything.
//
// Exactness. The three edges sit in lanes 0-2 of double vectors (lane 3 bounds nothing). n_i is an
// integer with |n_i| < 2^31 (a pixel of the tile, tile_edges.hpp), so q = n_i * (-1/gx_i), rounded
// twice, is within 2^-19 of the quotient, and the candidate c (ceil(q) for L, floor(q) for U) is
// within one of the bound. c is clamped to [u_first - 1, u_last + 1] (|c| <= 73: every value below is
// an integer under 2^53, so exact in double), then corrected by the edge's own test at c -/+ 1 and c:
// L = c - 1 + [G(c-1) < 0] + [G(c) < 0], U = c + 1 - [G(c+1) < 0] - [G(c) < 0] (G monotone in u).
// A clamped c only moves a bound that lies outside [u_first, u_last] to another value outside it,
// on the same side, so max(u_first, L) and min(u_last, U) are exact.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"

namespace rastercmp::cpu::fast {

struct RowColumns {
  __m256d n, gy, gx, inv;  // per edge: G - 1 at origin_x in the current row, its steps, -1 / gx
  __m256d lower;           // lanes with gx > 0 (all bits set)
  __m256d upper;           // lanes with gx < 0
  __m256d side;            // -1 for lower lanes, +1 otherwise: c + side is the first column tested
  __m256d u_first, u_last, clamp_lo, clamp_hi;
};

// Lanes 0-2 of a job's three-edge array as doubles, lane 3 zero (the 16-byte load reads the
// KernelJob field after the array, which the blend drops).
RASTERCMP_AVX2 inline __m256d edges_as_doubles(const int32_t (&edge)[3]) {
  const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(edge));
  return _mm256_cvtepi32_pd(_mm_blend_epi32(v, _mm_setzero_si128(), 0x8));
}

RASTERCMP_AVX2 inline RowColumns row_columns_of(const KernelJob& j) {
  static_assert(offsetof(KernelJob, gx) == offsetof(KernelJob, g_minus_1) + 12 &&
                offsetof(KernelJob, gy) == offsetof(KernelJob, gx) + 12 &&
                offsetof(KernelJob, gy) + 16 <= sizeof(KernelJob), "edges_as_doubles reads past each array");
  RowColumns c;
  c.gx = edges_as_doubles(j.gx);
  c.n = edges_as_doubles(j.g_minus_1);
  c.gy = edges_as_doubles(j.gy);
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  c.lower = _mm256_cmp_pd(c.gx, zero, _CMP_GT_OQ);
  c.upper = _mm256_cmp_pd(c.gx, zero, _CMP_LT_OQ);
  const __m256d flat = _mm256_cmp_pd(c.gx, zero, _CMP_EQ_OQ);
  c.inv = _mm256_andnot_pd(flat, _mm256_div_pd(_mm256_set1_pd(-1.0), _mm256_blendv_pd(c.gx, one, flat)));
  c.side = _mm256_blendv_pd(one, _mm256_set1_pd(-1.0), c.lower);
  c.u_first = _mm256_set1_pd(double(j.rect.x0 - j.origin_x));
  c.u_last = _mm256_set1_pd(double(j.rect.x1 - j.origin_x));
  c.clamp_lo = _mm256_sub_pd(c.u_first, one);
  c.clamp_hi = _mm256_add_pd(c.u_last, one);
  return c;
}

RASTERCMP_AVX2 inline double max4(__m256d v) {
  const __m128d m = _mm_max_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
  return _mm_cvtsd_f64(_mm_max_sd(m, _mm_unpackhi_pd(m, m)));
}

RASTERCMP_AVX2 inline double min4(__m256d v) {
  const __m128d m = _mm_min_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
  return _mm_cvtsd_f64(_mm_min_sd(m, _mm_unpackhi_pd(m, m)));
}

// The current row's covered columns [u0, u1] (offsets from origin_x; u0 > u1: none), then steps
// to the next row.
RASTERCMP_AVX2 inline void next_row_columns(RowColumns& c, int32_t& u0, int32_t& u1) {
  const __m256d q = _mm256_mul_pd(c.n, c.inv);
  __m256d cand = _mm256_blendv_pd(_mm256_floor_pd(q), _mm256_ceil_pd(q), c.lower);
  cand = _mm256_min_pd(_mm256_max_pd(cand, c.clamp_lo), c.clamp_hi);
  const __m256d outer = _mm256_add_pd(cand, c.side);                 // c - 1 (L) or c + 1 (U)
  const __m256d g_outer = _mm256_fmadd_pd(c.gx, outer, c.n);         // exact: integers below 2^53
  const __m256d g_cand = _mm256_fmadd_pd(c.gx, cand, c.n);
  const __m256d zero = _mm256_setzero_pd(), step = _mm256_sub_pd(zero, c.side);  // +1 (L), -1 (U)
  const __m256d bound =
      _mm256_add_pd(_mm256_add_pd(outer, _mm256_and_pd(_mm256_cmp_pd(g_outer, zero, _CMP_LT_OQ), step)),
                    _mm256_and_pd(_mm256_cmp_pd(g_cand, zero, _CMP_LT_OQ), step));
  c.n = _mm256_add_pd(c.n, c.gy);
  u0 = int32_t(max4(_mm256_blendv_pd(c.u_first, bound, c.lower)));
  u1 = int32_t(min4(_mm256_blendv_pd(c.u_last, bound, c.upper)));
}

// Rows [y0, y1] of the job narrowed to those every edge with gx = 0 covers (G - 1 = g + gy * k >= 0
// in row y0 + k); false when none is left. Integer arithmetic (int64), once per job.
inline bool flat_edge_rows(const KernelJob& j, int32_t& y0, int32_t& y1) {
  for (int i = 0; i < 3; ++i) {
    if (j.gx[i] != 0 || j.gy[i] == 0) continue;
    const int64_t g = j.g_minus_1[i], gy = j.gy[i];
    const auto floor_div = [](int64_t a, int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0))); };
    if (gy > 0) y0 = int32_t(std::max<int64_t>(y0, j.rect.y0 + -floor_div(g, gy)));  // k >= ceil(-g / gy)
    else y1 = int32_t(std::min<int64_t>(y1, j.rect.y0 + floor_div(g, -gy)));          // k <= floor(g / -gy)
  }
  return y0 <= y1;
}

// The rows of a job that hold a covered pixel, in order, with their covered columns.
struct CoveredRows {
  RowColumns columns;
  int32_t y = 0, y1 = -1, origin_x = 0;

  // The next such row y and its columns [x0, x1]; false after the last.
  RASTERCMP_AVX2 bool next(int32_t& row, int32_t& x0, int32_t& x1) {
    for (; y <= y1; ++y) {
      int32_t u0, u1;
      next_row_columns(columns, u0, u1);
      if (u0 > u1) continue;
      row = y++;
      x0 = origin_x + u0;
      x1 = origin_x + u1;
      return true;
    }
    return false;
  }
};

RASTERCMP_AVX2 inline CoveredRows covered_rows(const KernelJob& j) {
  CoveredRows rows;
  rows.y = j.rect.y0;
  rows.y1 = j.rect.y1;
  rows.origin_x = j.origin_x;
  if (!flat_edge_rows(j, rows.y, rows.y1)) return rows;
  rows.columns = row_columns_of(j);
  const __m256d skipped = _mm256_set1_pd(double(rows.y - j.rect.y0));  // rows cut by flat edges
  rows.columns.n = _mm256_add_pd(rows.columns.n, _mm256_mul_pd(rows.columns.gy, skipped));  // exact integers
  return rows;
}

}  // namespace rastercmp::cpu::fast
