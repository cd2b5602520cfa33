// The covered columns of each row of a kernel job, worked out from its edges (row_spans in
// tile_kernel_avx2.cpp, kernel16 in tile_kernel_avx512.cpp; include only from code compiled for
// AVX2 or AVX-512). In the "G" form (tile_edges.hpp)
// edge i covers the pixel at column offset u = x - origin_x of a row iff n_i + gx_i * u >= 0, with
// n_i its G - 1 at origin_x in that row: the covered columns of one edge are an interval, bounded
// below when gx_i > 0 (L = ceil(-n_i / gx_i)) and above when gx_i < 0 (U = floor(-n_i / gx_i)), and
// those of the triangle are their intersection. An edge with gx_i = 0 covers whole rows or none:
// its rows are cut once per job (flat_edge_rows); all-in edges (0, 0, 0) cover everything.
//
// Exactness. Four consecutive rows sit in the lanes of double vectors, one vector per bounding
// edge (rows in the lanes, 68726c2: one edge's operations serve four rows). n_i is an
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

// The bounding edges of a job, four consecutive rows in the lanes of each vector (lane k: row
// y + k): edges [0, lower) bound the columns below (gx > 0), [lower, count) above (gx < 0).
struct RowColumns {
  __m256d n[3];     // per bounding edge: G - 1 at origin_x in the batch's four rows
  __m256d step[3];  // 4 * gy: the next batch
  __m256d gx[3], inv[3];  // gx and -1 / gx
  int lower = 0, count = 0;
  __m256d u_first, u_last, clamp_lo, clamp_hi;
};

// The job's bounding edges for rows y0, y0 + 1, ... (y0 >= rect.y0: rows cut by flat edges skipped).
// Rows past the rectangle's last may be computed by the last batch; their values are not used.
RASTERCMP_AVX2 inline void init_row_columns(RowColumns& c, const KernelJob& j, int32_t y0) {
  const __m256d rows = _mm256_setr_pd(0, 1, 2, 3);
  int order[3], lower = 0, upper = 0;
  for (int i = 0; i < 3; ++i)
    if (j.gx[i] > 0) order[lower++] = i;
  for (int i = 0; i < 3; ++i)
    if (j.gx[i] < 0) order[lower + upper++] = i;
  c.lower = lower;
  c.count = lower + upper;
  for (int e = 0; e < c.count; ++e) {
    const int i = order[e];
    const __m256d gy = _mm256_set1_pd(double(j.gy[i]));
    const __m256d first = _mm256_add_pd(_mm256_set1_pd(double(j.g_minus_1[i])),  // exact integers
                                        _mm256_mul_pd(gy, _mm256_set1_pd(double(y0 - j.rect.y0))));
    c.n[e] = _mm256_fmadd_pd(gy, rows, first);
    c.step[e] = _mm256_mul_pd(gy, _mm256_set1_pd(4.0));
    c.gx[e] = _mm256_set1_pd(double(j.gx[i]));
    c.inv[e] = _mm256_set1_pd(-1.0 / double(j.gx[i]));
  }
  c.u_first = _mm256_set1_pd(double(j.rect.x0 - j.origin_x));
  c.u_last = _mm256_set1_pd(double(j.rect.x1 - j.origin_x));
  c.clamp_lo = _mm256_sub_pd(c.u_first, _mm256_set1_pd(1.0));
  c.clamp_hi = _mm256_add_pd(c.u_last, _mm256_set1_pd(1.0));
}

// The covered columns [u0[k], u1[k]] (offsets from origin_x; u0 > u1: none) of the batch's four
// rows, then steps to the next four.
RASTERCMP_AVX2 inline void next_row_columns(RowColumns& c, int32_t* u0, int32_t* u1) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  __m256d lo = c.u_first, hi = c.u_last;
  for (int e = 0; e < c.count; ++e) {
    const __m256d q = _mm256_mul_pd(c.n[e], c.inv[e]);
    const bool lower = e < c.lower;
    __m256d cand = lower ? _mm256_ceil_pd(q) : _mm256_floor_pd(q);
    cand = _mm256_min_pd(_mm256_max_pd(cand, c.clamp_lo), c.clamp_hi);
    const __m256d outer = lower ? _mm256_sub_pd(cand, one) : _mm256_add_pd(cand, one);  // c - 1 (L), c + 1 (U)
    const __m256d out_fails = _mm256_cmp_pd(_mm256_fmadd_pd(c.gx[e], outer, c.n[e]), zero, _CMP_LT_OQ);
    const __m256d cand_fails = _mm256_cmp_pd(_mm256_fmadd_pd(c.gx[e], cand, c.n[e]), zero, _CMP_LT_OQ);
    const __m256d moves = _mm256_add_pd(_mm256_and_pd(out_fails, one), _mm256_and_pd(cand_fails, one));
    if (lower)
      lo = _mm256_max_pd(lo, _mm256_add_pd(outer, moves));  // L = c - 1 + [G(c-1) < 0] + [G(c) < 0]
    else
      hi = _mm256_min_pd(hi, _mm256_sub_pd(outer, moves));  // U = c + 1 - [G(c+1) < 0] - [G(c) < 0]
    c.n[e] = _mm256_add_pd(c.n[e], c.step[e]);
  }
  _mm_storeu_si128(reinterpret_cast<__m128i*>(u0), _mm256_cvttpd_epi32(lo));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(u1), _mm256_cvttpd_epi32(hi));
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
  int32_t u0[4], u1[4];
  int k = 4;  // the next of the batch's rows in u0/u1 (4: none left)

  // The next such row y and its columns [x0, x1]; false after the last.
  RASTERCMP_AVX2 bool next(int32_t& row, int32_t& x0, int32_t& x1) {
    for (; y <= y1; ++y, ++k) {
      if (k == 4) {
        next_row_columns(columns, u0, u1);
        k = 0;
      }
      if (u0[k] > u1[k]) continue;
      row = y++;
      x0 = origin_x + u0[k];
      x1 = origin_x + u1[k++];
      return true;
    }
    return false;
  }
};

RASTERCMP_AVX2 inline void init_covered_rows(CoveredRows& rows, const KernelJob& j) {
  rows.y = j.rect.y0;
  rows.y1 = j.rect.y1;
  rows.origin_x = j.origin_x;
  flat_edge_rows(j, rows.y, rows.y1);  // no row left: y > y1, and next() computes nothing
  init_row_columns(rows.columns, j, rows.y);
}

}  // namespace rastercmp::cpu::fast
