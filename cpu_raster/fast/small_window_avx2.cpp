// The window compositor (small_window.hpp), eight pixels per AVX2 step: the algorithm of
// small_window_avx512.cpp on units of 4 columns x 2 rows instead of 8 x 2. The depth arithmetic
// is avx2_depth.hpp's, the scalar exact path's IEEE operations lane by lane (as the AVX2 kernels
// of tile_kernel_avx2.cpp do); the depth test is depth_passes8.
#include <immintrin.h>

#include <bit>

#include "cpu_raster/fast/avx2_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"
#include "cpu_raster/fast/small_window.hpp"

namespace rastercmp::cpu::fast {
namespace {

constexpr int kStrip = 8;  // pixels of one window row per load; a window row is kWindowWidth / kStrip strips
constexpr int kStrips = kWindowWidth / kStrip;
static_assert(kWindowWidth % kStrip == 0 && kGridSide <= kWindowWidth);

// The attachments' window in units of 4 columns x 2 rows, one ymm register each: unit (u, c) at
// [u][kUnit * c] holds window rows 2u (lanes 0-3) and 2u + 1 (lanes 4-7), columns 4c..4c+3. A
// triangle of a few pixels meets few units. 32-byte aligned (one register per unit).
constexpr int kUnitColumns = 4, kUnit = 8;
static_assert(kUnitColumns == 1 << 2 && kStrip == 2 * kUnitColumns);
struct Window {
  alignas(32) uint32_t owner[kWindowHeight / 2][kWindowWidth * 2];
  alignas(32) uint32_t depth[kWindowHeight / 2][kWindowWidth * 2];
};

RASTERCMP_AVX2 inline __m256i load8(const uint32_t* p) { return _mm256_load_si256(reinterpret_cast<const __m256i*>(p)); }
RASTERCMP_AVX2 inline void store8(uint32_t* p, __m256i v) { _mm256_store_si256(reinterpret_cast<__m256i*>(p), v); }

// One strip of an image row: 8 columns, of which the lanes set in `columns` lie in the window.
// A full strip (`full`) is moved whole; a partial one by maskload / maskstore, which never touch
// the columns past the window (they may be past the image row's end, or another worker's).
RASTERCMP_AVX2 inline __m256i load_strip(const uint32_t* p, __m256i columns, bool full) {
  if (full) return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
  return _mm256_maskload_epi32(reinterpret_cast<const int*>(p), columns);
}
RASTERCMP_AVX2 inline void store_strip(uint32_t* p, __m256i columns, bool full, __m256i v) {
  if (full)
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v);
  else
    _mm256_maskstore_epi32(reinterpret_cast<int*>(p), columns, v);
}

// Window rows 2u and 2u + 1 of attachment `image` (8 columns from x) to units (u, 2s) and
// (u, 2s + 1), and back; the second row only where `two_rows`.
RASTERCMP_AVX2 inline void load_units(const uint32_t* image, size_t row_pitch, __m256i columns, bool full,
                                      bool two_rows, uint32_t* unit) {
  const __m256i upper = load_strip(image, columns, full);
  const __m256i lower = two_rows ? load_strip(image + row_pitch, columns, full) : _mm256_setzero_si256();
  store8(unit, _mm256_permute2x128_si256(upper, lower, 0x20));
  store8(unit + kUnit, _mm256_permute2x128_si256(upper, lower, 0x31));
}

RASTERCMP_AVX2 inline void store_units(const uint32_t* unit, __m256i columns, bool full, bool two_rows,
                                       uint32_t* image, size_t row_pitch) {
  const __m256i left = load8(unit), right = load8(unit + kUnit);
  store_strip(image, columns, full, _mm256_permute2x128_si256(left, right, 0x20));
  if (two_rows) store_strip(image + row_pitch, columns, full, _mm256_permute2x128_si256(left, right, 0x31));
}

// Moves the window between the attachments and w (Load) or back (store).
template <bool Load>
RASTERCMP_AVX2 inline void move_window(Window& w, bool depth, int32_t wx0, int32_t wy0, int32_t width, int32_t height,
                                       const TileTarget& t) {
  const size_t pitch = size_t(t.width);
  const int strips = (width + kStrip - 1) / kStrip, unit_rows = (height + 1) / 2;
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (int s = 0; s < strips; ++s) {
    // Columns past the window but inside the image row are this worker's too (its rows, whole):
    // they are loaded and stored back unchanged. Only a strip that reaches past the row's end is
    // masked (maskstore is slow on AMD hosts).
    const int32_t in_row = t.width - (wx0 + kStrip * s);  // >= 1
    const bool full = in_row >= kStrip;
    const __m256i columns = _mm256_cmpgt_epi32(_mm256_set1_epi32(in_row), lane);
    for (int u = 0; u < unit_rows; ++u) {
      const bool two_rows = 2 * u + 1 < height;
      const size_t i = size_t(wy0 + 2 * u) * pitch + size_t(wx0 + kStrip * s);
      if constexpr (Load) {
        load_units(t.owner + i, pitch, columns, full, two_rows, &w.owner[u][2 * kUnit * s]);
        if (depth) load_units(t.depth + i, pitch, columns, full, two_rows, &w.depth[u][2 * kUnit * s]);
      } else {
        store_units(&w.owner[u][2 * kUnit * s], columns, full, two_rows, t.owner + i, pitch);
        if (depth) store_units(&w.depth[u][2 * kUnit * s], columns, full, two_rows, t.depth + i, pitch);
      }
    }
  }
}

// What every lane's loop starts from, for the eight lanes at once: its first and last unit row
// and column, E - 1 at the first unit's top-left pixel (e_window moved by whole rows and
// columns: 32-bit adds and multiplies wrap, so the order of the moves does not change the values,
// which lie in the window and at most one row above the lane's rows) and that pixel's y.
// `lanes`: the grid lanes with at least one row here.
struct LaneStarts {
  alignas(32) int32_t first_unit_row[8], last_unit_row[8], first_column[8], last_column[8];
  alignas(32) int32_t e[3][8];
  alignas(32) float first_y[8];
  uint32_t lanes = 0;
};

RASTERCMP_AVX2 inline __m256i load8(const int32_t* p) { return _mm256_load_si256(reinterpret_cast<const __m256i*>(p)); }
RASTERCMP_AVX2 inline void store8(int32_t* p, __m256i v) { _mm256_store_si256(reinterpret_cast<__m256i*>(p), v); }

RASTERCMP_AVX2 inline LaneStarts lane_starts(const SmallBlockOutput& b, int32_t row_lo, int32_t row_hi) {
  LaneStarts s;
  const __m256i wx0 = _mm256_set1_epi32(b.grid_x0), wy0 = _mm256_set1_epi32(row_lo), y0 = load8(b.y0);
  const __m256i y_first = _mm256_max_epi32(y0, wy0), y_last = _mm256_min_epi32(load8(b.y1), _mm256_set1_epi32(row_hi));
  const __m256i unit_row_first = _mm256_srai_epi32(_mm256_sub_epi32(y_first, wy0), 1);    // y_first >= row_lo
  const __m256i column_first = _mm256_srai_epi32(_mm256_sub_epi32(load8(b.x0), wx0), 2);  // x0 >= grid_x0
  const __m256i top = _mm256_add_epi32(wy0, _mm256_slli_epi32(unit_row_first, 1));  // y_first or y_first - 1
  const __m256i rows_down = _mm256_sub_epi32(top, y0), columns_right = _mm256_slli_epi32(column_first, 2);
  for (int k = 0; k < 3; ++k) {
    const __m256i down = _mm256_mullo_epi32(rows_down, load8(b.gy[k]));
    const __m256i right = _mm256_mullo_epi32(columns_right, load8(b.gx[k]));
    store8(s.e[k], _mm256_add_epi32(_mm256_add_epi32(load8(b.e_window[k]), down), right));
  }
  store8(s.first_unit_row, unit_row_first);
  store8(s.last_unit_row, _mm256_srai_epi32(_mm256_sub_epi32(y_last, wy0), 1));
  store8(s.first_column, column_first);
  store8(s.last_column, _mm256_srai_epi32(_mm256_sub_epi32(load8(b.x1), wx0), 2));
  _mm256_store_ps(s.first_y, _mm256_cvtepi32_ps(top));  // exact: integers below 2^24
  const uint32_t empty = uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(y_first, y_last))));
  s.lanes = b.grid_mask & ~empty;
  return s;
}

// One unit of lane l: coverage (the sign bit of e0 | e1 | e2 clear: every E - 1 >= 0), raw
// depth from the plane and the test against the window's depth, and the merge of the passing
// pixels (blends: the window is this call's own memory).
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 inline void composite_unit(const __m256i (&e)[3], __m256 inner, __m256 py, __m256 dzdy,
                                          const KernelDepth& kernel, __m256i owner, uint32_t* owners,
                                          uint32_t* depths) {
  const __m256i covered = _mm256_cmpgt_epi32(_mm256_or_si256(_mm256_or_si256(e[0], e[1]), e[2]), _mm256_set1_epi32(-1));
  __m256i pass = covered;
  if constexpr (F != DepthFormat::None) {
    // + o with o = 0 (small triangles come from draws without depth bias); the add turns -0 into +0
    const __m256 z = finish_depth8(mul_add8(dzdy, py, inner, kernel.fma), _mm256_setzero_ps(), kernel);
    const __m256i raw = to_raw<F>(z), stored = load8(depths);
    pass = _mm256_and_si256(covered, depth_passes8<F, Op>(z, raw, stored));
    if (kernel.write) store8(depths, _mm256_blendv_epi8(stored, raw, pass));
  }
  store8(owners, _mm256_blendv_epi8(load8(owners), owner, pass));
}

// A unit's pixels can lie outside a lane's rows: above its first row (a unit row that starts
// one row earlier) or below its last. There the lane covers nothing when the row is outside its
// bounding box too; the one row it may cover is row_hi + 1 (the lane's box reaches into another
// worker's rows), which is in the buffer (height odd: 2u + 1 = height <= 15) but never stored back.
// Columns likewise: a unit's columns past the lane's box are not covered by it, and those past
// the window's last column are in the buffer but never stored back.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 void composite(const SmallBlockOutput& b, uint32_t owner_of_lane_0, int32_t row_lo, int32_t row_hi,
                              const KernelDepth& kernel, const TileTarget& t) {
  constexpr bool kDepth = F != DepthFormat::None;
  const int32_t wx0 = b.grid_x0, wy0 = row_lo;
  const int32_t width = b.grid_x1 - wx0 + 1, height = row_hi - wy0 + 1;  // <= kWindowWidth, kWindowHeight
  Window w;
  move_window<true>(w, kDepth, wx0, wy0, width, height, t);
  const LaneStarts starts = lane_starts(b, row_lo, row_hi);
  const __m256i column_of = _mm256_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3);
  const __m256i row_of = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1);
  const __m256 px0 = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(wx0), column_of));  // exact: < 2^24
  const __m256 row_of_ps = _mm256_cvtepi32_ps(row_of);
  for (uint32_t lanes = starts.lanes; lanes != 0; lanes &= lanes - 1) {
    const int l = std::countr_zero(lanes);
    const __m256i owner = _mm256_set1_epi32(int32_t(owner_of_lane_0 + uint32_t(l)));
    __m256i e0[3], gy2[3], gx4[3];
    for (int k = 0; k < 3; ++k) {
      const __m256i gx = _mm256_set1_epi32(b.gx[k][l]), gy = _mm256_set1_epi32(b.gy[k][l]);
      const __m256i offsets = _mm256_add_epi32(_mm256_mullo_epi32(column_of, gx), _mm256_mullo_epi32(row_of, gy));
      e0[k] = _mm256_add_epi32(_mm256_set1_epi32(starts.e[k][l]), offsets);
      gy2[k] = _mm256_slli_epi32(gy, 1);
      gx4[k] = _mm256_slli_epi32(gx, 2);
    }
    const __m256 a0 = _mm256_set1_ps(b.a0[l]), dzdx = _mm256_set1_ps(b.dzdx[l]), dzdy = _mm256_set1_ps(b.dzdy[l]);
    const __m256 py0 = _mm256_add_ps(_mm256_set1_ps(starts.first_y[l]), row_of_ps);  // exact: integers below 2^24
    const int u_first = starts.first_unit_row[l], u_last = starts.last_unit_row[l];
    for (int c = starts.first_column[l];; ++c) {
      const __m256 px = _mm256_add_ps(px0, _mm256_set1_ps(float(kUnitColumns * c)));  // exact
      const __m256 inner = kDepth ? mul_add8(dzdx, px, a0, kernel.fma) : __m256{};   // FMA?(dzdx, px, a0)
      __m256 py = py0;
      __m256i e[3] = {e0[0], e0[1], e0[2]};
      for (int u = u_first; u <= u_last; ++u) {
        composite_unit<F, Op>(e, inner, py, dzdy, kernel, owner, &w.owner[u][kUnit * c], &w.depth[u][kUnit * c]);
        for (int k = 0; k < 3; ++k) e[k] = _mm256_add_epi32(e[k], gy2[k]);
        py = _mm256_add_ps(py, _mm256_set1_ps(2.0f));
      }
      if (c == starts.last_column[l]) break;
      for (int k = 0; k < 3; ++k) e0[k] = _mm256_add_epi32(e0[k], gx4[k]);
    }
  }
  move_window<false>(w, kDepth && kernel.write, wx0, wy0, width, height, t);
}

// Never draws nothing; the table still holds a compositor for it (the set-up does not know the op).
struct Windows {
  template <DepthFormat F, CompareOp Op>
  static constexpr WindowBlockFn get() {
    return &composite<F, Op>;
  }
};
constexpr auto kWindows = kernel_table<Windows>();  // [format][op] (format_dispatch.hpp)

}  // namespace

WindowBlockFn select_window_block_avx2(DepthFormat format, CompareOp op) { return select_kernel(kWindows, format, op); }

}  // namespace rastercmp::cpu::fast
