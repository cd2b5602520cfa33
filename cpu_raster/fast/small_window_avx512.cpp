// The window compositor (small_window.hpp), sixteen pixels per AVX-512 step. The depth arithmetic
// is avx512_depth.hpp's (avx2_depth.hpp's, operation for operation, on sixteen lanes).
#include <immintrin.h>

#include <algorithm>
#include <array>
#include <bit>
#include <utility>

#include "cpu_raster/fast/avx512_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"
#include "cpu_raster/fast/small_window.hpp"
#include "cpu_raster/fast/small_window_lanes.hpp"

namespace rastercmp::cpu::fast {
namespace {

constexpr int kStrip = 16;  // pixels per step; a window row is kWindowWidth / kStrip strips
static_assert(kWindowWidth == 2 * kStrip && kGridSide <= kStrip);

// The attachments' window in units of 8 columns x 2 rows, one zmm register each: unit (u, c) at
// [u][kUnit * c] holds window rows 2u (lanes 0-7) and 2u + 1 (lanes 8-15), columns 8c..8c+7. A
// triangle of a few pixels meets fewer units than 16-pixel row strips. 64-byte aligned, so
// that a lane's full-width store is forwarded to the next lane's load of the same unit.
constexpr int kUnitColumns = 8, kUnit = 16;
struct Window {
  alignas(64) uint32_t owner[kWindowHeight / 2][kWindowWidth * 2];
  alignas(64) uint32_t depth[kWindowHeight / 2][kWindowWidth * 2];
};

// Window rows 2u and 2u + 1 of attachment `image` (16 columns from x, `columns` of them in the
// window) to units (u, 2s) and (u, 2s + 1), and back; the second row only where `two_rows`.
RASTERCMP_AVX512 inline void load_units(const uint32_t* image, size_t row_pitch, __mmask16 columns, bool two_rows,
                                        uint32_t* unit) {
  const __m512i upper = _mm512_maskz_loadu_epi32(columns, image);
  const __m512i lower = two_rows ? _mm512_maskz_loadu_epi32(columns, image + row_pitch) : _mm512_setzero_si512();
  _mm512_store_si512(unit, _mm512_shuffle_i64x2(upper, lower, _MM_SHUFFLE(1, 0, 1, 0)));
  _mm512_store_si512(unit + kUnit, _mm512_shuffle_i64x2(upper, lower, _MM_SHUFFLE(3, 2, 3, 2)));
}

RASTERCMP_AVX512 inline void store_units(const uint32_t* unit, __mmask16 columns, bool two_rows, uint32_t* image,
                                         size_t row_pitch) {
  const __m512i left = _mm512_load_si512(unit), right = _mm512_load_si512(unit + kUnit);
  _mm512_mask_storeu_epi32(image, columns, _mm512_shuffle_i64x2(left, right, _MM_SHUFFLE(1, 0, 1, 0)));
  if (two_rows)
    _mm512_mask_storeu_epi32(image + row_pitch, columns, _mm512_shuffle_i64x2(left, right, _MM_SHUFFLE(3, 2, 3, 2)));
}

// A unit's pixels can lie outside a lane's rows: above its first row (a unit row that starts
// one row earlier) or below its last. There the lane covers nothing when the row is outside its
// bounding box too; the one row it may cover is row_hi + 1 (the lane's box reaches into another
// worker's rows), which is in the buffer (height odd: 2u + 1 = height <= 15) but never stored back.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 void composite(const SmallBlockOutput& b, uint32_t owner_of_lane_0, int32_t row_lo, int32_t row_hi,
                                const KernelDepth& kernel, const TileTarget& t) {
  constexpr bool kDepth = F != DepthFormat::None;
  const Depth16 depth = depth16(kernel);
  const int32_t wx0 = b.grid_x0, wy0 = row_lo;
  const int32_t width = b.grid_x1 - wx0 + 1, height = row_hi - wy0 + 1;  // <= kWindowWidth, kWindowHeight
  const int strips = width > kStrip ? 2 : 1, unit_rows = (height + 1) / 2;
  const __mmask16 columns[2] = {__mmask16(width >= kStrip ? 0xFFFFu : (1u << width) - 1u),
                                __mmask16(width > kStrip ? (1u << (width - kStrip)) - 1u : 0u)};
  const size_t pitch = size_t(t.width);
  Window w;
  for (int u = 0; u < unit_rows; ++u) {
    const bool two_rows = 2 * u + 1 < height;
    for (int s = 0; s < strips; ++s) {
      const size_t i = size_t(wy0 + 2 * u) * pitch + size_t(wx0 + kStrip * s);
      load_units(t.owner + i, pitch, columns[s], two_rows, &w.owner[u][2 * kUnit * s]);
      if constexpr (kDepth) load_units(t.depth + i, pitch, columns[s], two_rows, &w.depth[u][2 * kUnit * s]);
    }
  }
  const LaneStarts starts = lane_starts<1>(b, row_lo, row_hi);  // units of two rows
  static_assert(kUnitColumns == 1 << kLaneUnitColumnsLog2);
  const __m512i column_of = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7);
  const __m512i row_of = _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1);
  const __m512 px0 = _mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(wx0), column_of));  // exact: < 2^24
  const __m512 row_of_ps = _mm512_cvtepi32_ps(row_of);
  for (uint32_t lanes = starts.lanes; lanes != 0; lanes &= lanes - 1) {
    const int l = std::countr_zero(lanes);
    const __m512i owner = _mm512_set1_epi32(int32_t(owner_of_lane_0 + uint32_t(l)));
    __m512i e0[3], gy2[3];
    for (int k = 0; k < 3; ++k) {
      const __m512i gx = _mm512_set1_epi32(b.gx[k][l]), gy = _mm512_set1_epi32(b.gy[k][l]);
      const __m512i offsets = _mm512_add_epi32(_mm512_mullo_epi32(column_of, gx), _mm512_mullo_epi32(row_of, gy));
      e0[k] = _mm512_add_epi32(_mm512_set1_epi32(starts.e[k][l]), offsets);
      gy2[k] = _mm512_slli_epi32(gy, 1);
    }
    const __m512 a0 = _mm512_set1_ps(b.a0[l]), dzdx = _mm512_set1_ps(b.dzdx[l]), dzdy = _mm512_set1_ps(b.dzdy[l]);
    const __m512 py0 = _mm512_add_ps(_mm512_set1_ps(starts.first_y[l]), row_of_ps);  // exact: integers below 2^24
    const int u_first = starts.first_unit_row[l], u_last = starts.last_unit_row[l];
    for (int c = starts.first_column[l];; ++c) {
      const __m512 px = _mm512_add_ps(px0, _mm512_set1_ps(float(kUnitColumns * c)));  // exact
      const __m512 inner = kDepth ? mul_add16(dzdx, px, a0, depth.fma) : __m512{};    // FMA?(dzdx, px, a0)
      __m512 py = py0;
      __m512i e[3] = {e0[0], e0[1], e0[2]};
      for (int u = u_first; u <= u_last; ++u) {
        // covered: every E - 1 >= 0, i.e. the sign bit of e0 | e1 | e2 clear
        const __mmask16 covered =
            _mm512_cmpge_epi32_mask(_mm512_ternarylogic_epi32(e[0], e[1], e[2], 0xFE), _mm512_setzero_si512());
        __mmask16 pass = covered;
        if constexpr (kDepth) {
          const __m512 z = finish_depth16(mul_add16(dzdy, py, inner, depth.fma), depth);
          const __m512i raw = to_raw16<F>(z);
          uint32_t* unit = &w.depth[u][kUnit * c];
          const __m512i stored = _mm512_load_si512(unit);
          pass = passing<F, Op>(covered, raw, stored);
          if (depth.write) _mm512_mask_store_epi32(unit, pass, raw);
        }
        uint32_t* owners = &w.owner[u][kUnit * c];
        _mm512_store_si512(owners, _mm512_mask_mov_epi32(_mm512_load_si512(owners), pass, owner));
        for (int k = 0; k < 3; ++k) e[k] = _mm512_add_epi32(e[k], gy2[k]);
        py = _mm512_add_ps(py, _mm512_set1_ps(2.0f));
      }
      if (c == starts.last_column[l]) break;
      for (int k = 0; k < 3; ++k) e0[k] = _mm512_add_epi32(e0[k], _mm512_slli_epi32(_mm512_set1_epi32(b.gx[k][l]), 3));
    }
  }
  for (int u = 0; u < unit_rows; ++u) {
    const bool two_rows = 2 * u + 1 < height;
    for (int s = 0; s < strips; ++s) {
      const size_t i = size_t(wy0 + 2 * u) * pitch + size_t(wx0 + kStrip * s);
      store_units(&w.owner[u][2 * kUnit * s], columns[s], two_rows, t.owner + i, pitch);
      if (kDepth && depth.write) store_units(&w.depth[u][2 * kUnit * s], columns[s], two_rows, t.depth + i, pitch);
    }
  }
}

struct Windows {
  template <DepthFormat F, CompareOp Op>
  static constexpr WindowBlockFn get() {
    return &composite<F, Op>;
  }
};
constexpr auto kWindows = kernel_table<Windows>();  // [format][op] (format_dispatch.hpp)

}  // namespace

WindowBlockFn select_window_block_avx512(DepthFormat format, CompareOp op) {
  return select_kernel(kWindows, format, op);
}

}  // namespace rastercmp::cpu::fast
