// What every lane of a window block (small_window.hpp) starts its loop from, worked out for the
// eight lanes at once by both compositors (small_window_avx2.cpp: units of 8 columns x 1 row;
// small_window_avx512.cpp: 8 columns x 2 rows).
#pragma once

#include <immintrin.h>

#include <cstdint>

#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/small_triangles.hpp"

namespace rastercmp::cpu::fast {

// Per lane: its first and last unit row (window rows from row_lo, 1 << kUnitRowsLog2 to a unit)
// within [row_lo, row_hi], its first and last unit column (8 columns from grid_x0 to a unit), E -
// 1 at the first unit's top-left pixel (e_window moved by whole rows and columns: 32-bit adds and
// multiplies wrap, so the order of the moves does not change the values, which lie in the window
// and, with units of two rows, at most one row above the lane's rows) and that pixel's y. `lanes`:
// the grid lanes with at least one row here.
struct LaneStarts {
  alignas(32) int32_t first_unit_row[8], last_unit_row[8], first_column[8], last_column[8];
  alignas(32) int32_t e[3][8];
  alignas(32) float first_y[8];
  uint32_t lanes = 0;
};

inline constexpr int kLaneUnitColumnsLog2 = 3;

RASTERCMP_AVX2 inline __m256i load_lane_words(const int32_t* p) {
  return _mm256_load_si256(reinterpret_cast<const __m256i*>(p));
}
RASTERCMP_AVX2 inline void store_lane_words(int32_t* p, __m256i v) {
  _mm256_store_si256(reinterpret_cast<__m256i*>(p), v);
}

template <int kUnitRowsLog2>
RASTERCMP_AVX2 inline LaneStarts lane_starts(const SmallBlockOutput& b, int32_t row_lo, int32_t row_hi) {
  LaneStarts s;
  const __m256i wx0 = _mm256_set1_epi32(b.grid_x0), wy0 = _mm256_set1_epi32(row_lo), y0 = load_lane_words(b.y0);
  const __m256i y_first = _mm256_max_epi32(y0, wy0),
                y_last = _mm256_min_epi32(load_lane_words(b.y1), _mm256_set1_epi32(row_hi));
  const __m256i unit_row_first = _mm256_srai_epi32(_mm256_sub_epi32(y_first, wy0), kUnitRowsLog2);  // y_first >= row_lo
  const __m256i column_first =
      _mm256_srai_epi32(_mm256_sub_epi32(load_lane_words(b.x0), wx0), kLaneUnitColumnsLog2);    // x0 >= grid_x0
  const __m256i top = _mm256_add_epi32(wy0, _mm256_slli_epi32(unit_row_first, kUnitRowsLog2));  // y_first or one above
  const __m256i rows_down = _mm256_sub_epi32(top, y0);
  const __m256i columns_right = _mm256_slli_epi32(column_first, kLaneUnitColumnsLog2);
  for (int k = 0; k < 3; ++k) {
    const __m256i down = _mm256_mullo_epi32(rows_down, load_lane_words(b.gy[k]));
    const __m256i right = _mm256_mullo_epi32(columns_right, load_lane_words(b.gx[k]));
    store_lane_words(s.e[k], _mm256_add_epi32(_mm256_add_epi32(load_lane_words(b.e_window[k]), down), right));
  }
  store_lane_words(s.first_unit_row, unit_row_first);
  store_lane_words(s.last_unit_row, _mm256_srai_epi32(_mm256_sub_epi32(y_last, wy0), kUnitRowsLog2));
  store_lane_words(s.first_column, column_first);
  store_lane_words(s.last_column,
                   _mm256_srai_epi32(_mm256_sub_epi32(load_lane_words(b.x1), wx0), kLaneUnitColumnsLog2));
  _mm256_store_ps(s.first_y, _mm256_cvtepi32_ps(top));  // exact: integers below 2^24
  const uint32_t empty = uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(y_first, y_last))));
  s.lanes = b.grid_mask & ~empty;
  return s;
}

}  // namespace rastercmp::cpu::fast
