// The covered columns of the AVX2 exact rows (exact_rows.hpp; plane_rows_avx2.cpp sets the planes'
// rows up, exact_rows_avx2.cpp draws frames of one sample per pixel and the queue,
// exact_rows_4x_avx2.cpp per-sample primitives in 4x frames): every plane's columns of four sample
// rows per vector step, then the covered samples' raw depths, depth tests and stored values eight
// at a time.
//
// Coverage. For a sample row (sample point y Y, x offset sx in fixed units), plane i's value at
// column px is E(px) = k - d * px with k = E at column 0 and d = dcdx * 256: an integer, covered
// iff n(px) = E(px) - 1 >= 0. In the form of row_columns_avx2.hpp (n + gx * u >= 0, gx = -d) the
// covered columns of a plane with d < 0 are bounded below by L = ceil(-n / gx), those of one with
// d > 0 above by U = floor(-n / gx); a plane with d = 0 covers the whole row or none (n >= 0).
// Four consecutive rows sit in the lanes of a double vector.
//
// Exactness. A primitive is taken only when, for every plane, |n| <= 2^51 in the first row and in
// the last row a batch computes (n is linear in the row, so in every row between) and
// |d| * (max(|x0|, |x1|) + 2) <= 2^51 for its visit columns [x0, x1]: then every n, every
// n + gx * u for u in [x0 - 2, x1 + 2] and every row step is an integer below 2^53, exact in
// double (the FMA rounds once, an exact value not at all), so each test n + gx * u < 0 is the exact
// path's E <= 0. The candidate c = ceil(q) or floor(q), q = n * (-1 / gx) rounded twice, is within
// 2^43 * 3 * 2^-53 < 1 of -n / gx (|n / gx| <= 2^51 / 256), so within one of the bound; clamped to
// [x0 - 1, x1 + 1] and corrected by the plane's own test at c -/+ 1 and c (row_columns_avx2.hpp's
// argument), max(x0, L) and min(x1, U) are the exact interval. The sample grid: sample_point's
// fixed offsets and floats (px as float, plus the sample's x offset: the same conversion and add).
//
// Depth. A covered (column, sample) gets z = fl(FMA?(dzdy, y, FMA?(dzdx, x, a0)) + o), clamped and
// converted (avx2_depth.hpp: sample_depth's operations, one intrinsic each, at sample_point's x and
// y), is tested against the stored value (depth_passes: depth_test_passes' predicates), and a
// passing one is written as write_covered_sample writes it. A batch or step holds samples of one
// primitive only, all distinct, so reading its stored values before writing any reads what the
// exact path's sample by sample order reads.
#pragma once

#include <immintrin.h>

#include <cstdint>

#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/exact_rows.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"

namespace rastercmp::cpu::fast {

inline constexpr int64_t kExactBound = int64_t(1) << 51;

// A primitive's planes for the rows of its samples, four rows per step, grouped by the bound they
// give: [0, lower) bound the columns below, [lower, upper) above, [upper, count) are flat. n[s]
// holds sample s's values in the next step's four rows (from start_sample on).
struct PlaneRows {
  __m256d n[4][8], step[8], gx[8], inv[8];
  double dy[8];
  double first[4][8];
  uint32_t lower = 0, upper = 0, count = 0;
};

// The planes of p for rows y0, y0 + 1, ... of each tested sample; false when a value leaves the
// bounds above (rows up to y1 + 3 are checked: the last step may compute them; |dcdx|, |dcdy| <=
// 2^30 and |x| <= 2^20 keep the checks themselves inside int64).
RASTERCMP_AVX2 bool init_plane_rows(PlaneRows& rows, const RasterPrimitive& p, uint32_t samples, int32_t y0,
                                    int32_t y1);
// Its two ways, which init_plane_rows picks between: plane by plane (any planes and samples), and
// four planes of one sample at once (a line's), which declines (false) wherever a check fails or a
// value nears the bounds, leaving the verdict to the other.
RASTERCMP_AVX2 bool init_plane_rows_each(PlaneRows& rows, const RasterPrimitive& p, uint32_t samples, int32_t y0,
                                         int32_t y1);
RASTERCMP_AVX2 bool init_four_plane_rows(PlaneRows& rows, const RasterPrimitive& p, int32_t y0, int32_t y1);

// The values of sample s in rows y0 to y0 + 3.
RASTERCMP_AVX2 inline void start_sample(PlaneRows& rows, uint32_t s) {
  const __m256d lanes = _mm256_setr_pd(0, 1, 2, 3);
  for (uint32_t e = 0; e < rows.count; ++e)
    rows.n[s][e] = _mm256_fmadd_pd(_mm256_set1_pd(rows.dy[e]), lanes, _mm256_set1_pd(rows.first[s][e]));
}

// Plane e's bound on the covered columns in each of the step's four rows (n its values there),
// from c, ceil or floor of n * (-1 / gx) clamped to [clamp_lo, clamp_hi]: for a plane bounding below
// (kLeast) the least, L = c - 1 + [G(c-1) < 0] + [G(c) < 0]; for one bounding above the greatest,
// U = c + 1 - [G(c+1) < 0] - [G(c) < 0].
template <bool kLeast>
RASTERCMP_AVX2 inline __m256d bound_columns(const PlaneRows& rows, uint32_t e, __m256d n, __m256d clamp_lo,
                                            __m256d clamp_hi) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  const __m256d q = _mm256_mul_pd(n, rows.inv[e]);
  const __m256d c = _mm256_min_pd(_mm256_max_pd(kLeast ? _mm256_ceil_pd(q) : _mm256_floor_pd(q), clamp_lo), clamp_hi);
  const __m256d outer = kLeast ? _mm256_sub_pd(c, one) : _mm256_add_pd(c, one);
  const __m256d out_fails = _mm256_cmp_pd(_mm256_fmadd_pd(rows.gx[e], outer, n), zero, _CMP_LT_OQ);
  const __m256d c_fails = _mm256_cmp_pd(_mm256_fmadd_pd(rows.gx[e], c, n), zero, _CMP_LT_OQ);
  const __m256d fails = _mm256_add_pd(_mm256_and_pd(out_fails, one), _mm256_and_pd(c_fails, one));
  return kLeast ? _mm256_add_pd(outer, fails) : _mm256_sub_pd(outer, fails);
}

// The covered columns [u0[k], u1[k]] (u0 > u1: none) of sample s in the step's four rows, then the
// sample's next step.
RASTERCMP_AVX2 inline void next_plane_rows(PlaneRows& rows, uint32_t s, __m256d first, __m256d last, int32_t* u0,
                                           int32_t* u1) {
  __m256d* n = rows.n[s];
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d clamp_lo = _mm256_sub_pd(first, one), clamp_hi = _mm256_add_pd(last, one);
  __m256d lo = first, hi = last;
  for (uint32_t e = 0; e < rows.lower; ++e) {
    lo = _mm256_max_pd(lo, bound_columns<true>(rows, e, n[e], clamp_lo, clamp_hi));
    n[e] = _mm256_add_pd(n[e], rows.step[e]);
  }
  for (uint32_t e = rows.lower; e < rows.upper; ++e) {
    hi = _mm256_min_pd(hi, bound_columns<false>(rows, e, n[e], clamp_lo, clamp_hi));
    n[e] = _mm256_add_pd(n[e], rows.step[e]);
  }
  for (uint32_t e = rows.upper; e < rows.count; ++e) {  // flat: the whole row (n >= 0) or none
    lo = _mm256_blendv_pd(lo, clamp_hi, _mm256_cmp_pd(n[e], _mm256_setzero_pd(), _CMP_LT_OQ));
    n[e] = _mm256_add_pd(n[e], rows.step[e]);
  }
  _mm_storeu_si128(reinterpret_cast<__m128i*>(u0), _mm256_cvttpd_epi32(lo));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(u1), _mm256_cvttpd_epi32(hi));
}

// A line's parallelogram (a line's planes 0 to 3 are the edges from vertex_fixed[i] to
// vertex_fixed[i + 1], as both line set-ups make them; here also v0 + v2 = v1 + v3): the sample rows
// [first_row, last_row] where its "caps", edges 1 and 3, cannot bind, and the places in PlaneRows of
// its long edges 0 and 2, one bounding below (`lower`), one above. Cap k's line meets the strip
// between the long edges' lines only in the cap, whose y range is its corners'; a sample row outside
// both caps' ranges and between them crosses the strip on the side of each cap that holds the other,
// so every sample of it that passes both long edges is strictly on the inner side of both caps:
// where the long edges' columns are not empty they are the four planes' (where the parallelogram is
// wound the other way, the long edges' covered half-planes do not meet, and both are empty). Empty
// (first_row > last_row) where p is not such a line, a cap is level with the other, or a long edge
// is flat.
struct ParallelogramMiddle {
  int32_t first_row = 1, last_row = 0;
  uint32_t lower = 0, upper = 0;
};
RASTERCMP_AVX2 ParallelogramMiddle parallelogram_middle(const RasterPrimitive& p, const PlaneRows& rows);
// Rows below which thin_rows does not look for a middle: working one out costs about 100
// instructions and a middle step saves about 25, so a line needs four middle steps to gain
// (instructions a line of lines_20k: 4,597 from 8 rows, 4,589 from 16, 4,595 from 24;
// docs/performance-log.md, "A line's middle rows without its caps").
inline constexpr int32_t kMiddleMinRows = 16;

// next_plane_rows in the middle rows of a parallelogram: the columns from its long edges alone, every
// plane's values stepped.
RASTERCMP_AVX2 inline void next_middle_rows(PlaneRows& rows, const ParallelogramMiddle& middle, uint32_t s,
                                            __m256d first, __m256d last, int32_t* u0, int32_t* u1) {
  __m256d* n = rows.n[s];
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d clamp_lo = _mm256_sub_pd(first, one), clamp_hi = _mm256_add_pd(last, one);
  const __m256d lo = _mm256_max_pd(first, bound_columns<true>(rows, middle.lower, n[middle.lower], clamp_lo, clamp_hi));
  const __m256d hi = _mm256_min_pd(last, bound_columns<false>(rows, middle.upper, n[middle.upper], clamp_lo, clamp_hi));
  for (uint32_t e = 0; e < rows.count; ++e) n[e] = _mm256_add_pd(n[e], rows.step[e]);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(u0), _mm256_cvttpd_epi32(lo));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(u1), _mm256_cvttpd_epi32(hi));
}

// A per-sample primitive in a 4x frame with an active depth test (exact_rows_4x_avx2.cpp): the
// same writes as rasterize_primitive's for its rows [y0, y1]; false, having written nothing, when
// its planes leave the bounds above.
using SampleRowsFn = bool (*)(const RasterPrimitive&, int32_t, int32_t, const KernelDepth&, RenderTargets&);
SampleRowsFn select_sample_rows_avx2(DepthFormat format, CompareOp op);  // null without depth

}  // namespace rastercmp::cpu::fast
