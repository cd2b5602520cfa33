// The window compositor (small_window.hpp), sixteen pixels per AVX-512 step. The depth arithmetic
// is avx512_depth.hpp's (avx2_depth.hpp's, operation for operation, on sixteen lanes).
#include <immintrin.h>

// GCC 12's own AVX-512 headers pass _mm512_undefined_ps() as the merge source of vminps and
// friends, which -Wuninitialized reports at every use once inlined (a false positive: unmasked).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <utility>

#include "cpu_raster/fast/avx512_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/small_window.hpp"

namespace rastercmp::cpu::fast {
namespace {

constexpr int kStrip = 16;  // pixels per step; a window row is kWindowWidth / kStrip strips
static_assert(kWindowWidth == 2 * kStrip && kGridSide <= kStrip);

// depth_test_passes (§3.6) on the covered lanes: D32 with the unordered predicates (true whenever
// NaN is involved), UNORM unsigned.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 inline __mmask16 passing(__mmask16 covered, __m512i fragment, __m512i stored) {
  if constexpr (F == DepthFormat::None || Op == CompareOp::Always) {
    return covered;
  } else if constexpr (Op == CompareOp::Never) {
    return 0;
  } else if constexpr (F == DepthFormat::D32Sfloat) {
    const __m512 a = _mm512_castsi512_ps(fragment), b = _mm512_castsi512_ps(stored);
    if constexpr (Op == CompareOp::Less) return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NGE_UQ);  // !(a >= b)
    if constexpr (Op == CompareOp::Equal) return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_EQ_UQ);  // !(a < b) && !(a > b)
    if constexpr (Op == CompareOp::LessOrEqual) return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NGT_UQ);
    if constexpr (Op == CompareOp::Greater) return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NLE_UQ);
    if constexpr (Op == CompareOp::NotEqual) return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NEQ_UQ);
    return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NLT_UQ);  // GreaterOrEqual: !(a < b)
  } else {
    if constexpr (Op == CompareOp::Less) return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_LT);
    if constexpr (Op == CompareOp::Equal) return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_EQ);
    if constexpr (Op == CompareOp::LessOrEqual) return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_LE);
    if constexpr (Op == CompareOp::Greater) return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_NLE);
    if constexpr (Op == CompareOp::NotEqual) return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_NE);
    return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_NLT);  // GreaterOrEqual
  }
}

// The attachments' window, row r strip s at [r][kStrip * s], 64-byte aligned so that a lane's
// full-width store is forwarded to the next lane's load of the same strip.
struct Window {
  alignas(64) uint32_t owner[kWindowHeight][kWindowWidth];
  alignas(64) uint32_t depth[kWindowHeight][kWindowWidth];
};

// What every lane's loop starts from, for the eight lanes at once: its rows within [row_lo, row_hi]
// as window rows, its first and last strip, E - 1 at column 0 of its first strip on its first
// row (e_window moved by whole rows and strips: 32-bit adds and multiplies wrap, so the order of
// the moves does not change the values, which lie in the lane's own rows and the window), and
// the first row's y. `lanes`: the grid lanes with at least one row here.
struct LaneStarts {
  alignas(32) int32_t first_row[8], last_row[8], first_strip[8], last_strip[8];
  alignas(32) int32_t e[3][8];
  alignas(32) float first_y[8];
  uint32_t lanes = 0;
};

RASTERCMP_AVX512 inline __m256i load(const int32_t* p) { return _mm256_load_si256(reinterpret_cast<const __m256i*>(p)); }
RASTERCMP_AVX512 inline void store(int32_t* p, __m256i v) { _mm256_store_si256(reinterpret_cast<__m256i*>(p), v); }

RASTERCMP_AVX512 inline LaneStarts lane_starts(const SmallBlockOutput& b, int32_t row_lo, int32_t row_hi) {
  LaneStarts s;
  const __m256i wx0 = _mm256_set1_epi32(b.grid_x0), y0 = load(b.y0);
  const __m256i y_first = _mm256_max_epi32(y0, _mm256_set1_epi32(row_lo));
  const __m256i y_last = _mm256_min_epi32(load(b.y1), _mm256_set1_epi32(row_hi));
  const __m256i strip_first = _mm256_srai_epi32(_mm256_sub_epi32(load(b.x0), wx0), 4);  // x0 >= grid_x0
  static_assert(kStrip == 1 << 4);
  const __m256i rows_down = _mm256_sub_epi32(y_first, y0), columns_right = _mm256_slli_epi32(strip_first, 4);
  for (int k = 0; k < 3; ++k) {
    const __m256i down = _mm256_mullo_epi32(rows_down, load(b.gy[k]));
    const __m256i right = _mm256_mullo_epi32(columns_right, load(b.gx[k]));
    store(s.e[k], _mm256_add_epi32(_mm256_add_epi32(load(b.e_window[k]), down), right));
  }
  const __m256i wy0 = _mm256_set1_epi32(row_lo);
  store(s.first_row, _mm256_sub_epi32(y_first, wy0));
  store(s.last_row, _mm256_sub_epi32(y_last, wy0));
  store(s.first_strip, strip_first);
  store(s.last_strip, _mm256_srai_epi32(_mm256_sub_epi32(load(b.x1), wx0), 4));
  _mm256_store_ps(s.first_y, _mm256_cvtepi32_ps(y_first));  // exact: integers below 2^24
  const uint32_t empty = _mm256_cmpgt_epi32_mask(y_first, y_last);
  s.lanes = b.grid_mask & ~empty;
  return s;
}

template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 void composite(const SmallBlockOutput& b, uint32_t owner_of_lane_0, int32_t row_lo, int32_t row_hi,
                                const KernelDepth& kernel, const TileTarget& t) {
  constexpr bool kDepth = F != DepthFormat::None;
  const Depth16 depth = depth16(kernel);
  const int32_t wx0 = b.grid_x0, wy0 = row_lo;
  const int32_t width = b.grid_x1 - wx0 + 1, height = row_hi - wy0 + 1;  // <= kWindowWidth, kWindowHeight
  const int strips = width > kStrip ? 2 : 1;
  const __mmask16 columns[2] = {__mmask16(width >= kStrip ? 0xFFFFu : (1u << width) - 1u),
                                __mmask16(width > kStrip ? (1u << (width - kStrip)) - 1u : 0u)};
  Window w;
  for (int32_t r = 0; r < height; ++r) {
    for (int s = 0; s < strips; ++s) {
      const size_t i = size_t(wy0 + r) * size_t(t.width) + size_t(wx0 + kStrip * s);
      _mm512_store_si512(&w.owner[r][kStrip * s], _mm512_maskz_loadu_epi32(columns[s], t.owner + i));
      if constexpr (kDepth) _mm512_store_si512(&w.depth[r][kStrip * s], _mm512_maskz_loadu_epi32(columns[s], t.depth + i));
    }
  }
  const LaneStarts starts = lane_starts(b, row_lo, row_hi);
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512 px0 = _mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(wx0), iota));  // exact: < 2^24
  for (uint32_t lanes = starts.lanes; lanes != 0; lanes &= lanes - 1) {
    const int l = std::countr_zero(lanes);
    const __m512i owner = _mm512_set1_epi32(int32_t(owner_of_lane_0 + uint32_t(l)));
    __m512i e0[3], gy[3];
    for (int k = 0; k < 3; ++k) {
      e0[k] = _mm512_add_epi32(_mm512_set1_epi32(starts.e[k][l]), _mm512_mullo_epi32(iota, _mm512_set1_epi32(b.gx[k][l])));
      gy[k] = _mm512_set1_epi32(b.gy[k][l]);
    }
    const __m512 a0 = _mm512_set1_ps(b.a0[l]), dzdx = _mm512_set1_ps(b.dzdx[l]), dzdy = _mm512_set1_ps(b.dzdy[l]);
    const int32_t r_first = starts.first_row[l], r_last = starts.last_row[l];
    for (int s = starts.first_strip[l];; ++s) {
      const __m512 px = s == 0 ? px0 : _mm512_add_ps(px0, _mm512_set1_ps(float(kStrip)));  // exact
      const __m512 inner = kDepth ? mul_add16(dzdx, px, a0, depth.fma) : __m512{};  // FMA?(dzdx, px, a0)
      __m512 py = _mm512_set1_ps(starts.first_y[l]);  // exact: integers below 2^24
      __m512i e[3] = {e0[0], e0[1], e0[2]};
      for (int32_t r = r_first; r <= r_last; ++r) {
        // covered: every E - 1 >= 0, i.e. the sign bit of e0 | e1 | e2 clear
        const __mmask16 covered = _mm512_cmpge_epi32_mask(_mm512_ternarylogic_epi32(e[0], e[1], e[2], 0xFE),
                                                          _mm512_setzero_si512());
        __mmask16 pass = covered;
        if constexpr (kDepth) {
          const __m512 z = finish_depth16(mul_add16(dzdy, py, inner, depth.fma), depth);
          const __m512i raw = to_raw16<F>(z);
          uint32_t* row = &w.depth[r][kStrip * s];
          const __m512i stored = _mm512_load_si512(row);
          pass = passing<F, Op>(covered, raw, stored);
          if (depth.write) _mm512_store_si512(row, _mm512_mask_mov_epi32(stored, pass, raw));
        }
        uint32_t* owners = &w.owner[r][kStrip * s];
        _mm512_store_si512(owners, _mm512_mask_mov_epi32(_mm512_load_si512(owners), pass, owner));
        for (int k = 0; k < 3; ++k) e[k] = _mm512_add_epi32(e[k], gy[k]);
        py = _mm512_add_ps(py, _mm512_set1_ps(1.0f));
      }
      if (s == starts.last_strip[l]) break;
      for (int k = 0; k < 3; ++k) e0[k] = _mm512_add_epi32(e0[k], _mm512_slli_epi32(_mm512_set1_epi32(b.gx[k][l]), 4));
    }
  }
  for (int32_t r = 0; r < height; ++r) {
    for (int s = 0; s < strips; ++s) {
      const size_t i = size_t(wy0 + r) * size_t(t.width) + size_t(wx0 + kStrip * s);
      _mm512_mask_storeu_epi32(t.owner + i, columns[s], _mm512_load_si512(&w.owner[r][kStrip * s]));
      if (kDepth && depth.write) _mm512_mask_storeu_epi32(t.depth + i, columns[s], _mm512_load_si512(&w.depth[r][kStrip * s]));
    }
  }
}

template <DepthFormat F, size_t... I>
constexpr std::array<WindowBlockFn, 8> windows_for(std::index_sequence<I...>) {
  return {&composite<F, CompareOp(I)>...};
}

constexpr std::array<std::array<WindowBlockFn, 8>, 4> kWindows = {
    windows_for<DepthFormat::None>(std::make_index_sequence<8>{}),
    windows_for<DepthFormat::D16Unorm>(std::make_index_sequence<8>{}),
    windows_for<DepthFormat::X8D24Unorm>(std::make_index_sequence<8>{}),
    windows_for<DepthFormat::D32Sfloat>(std::make_index_sequence<8>{}),
};

}  // namespace

WindowBlockFn select_window_block_avx512(DepthFormat format, CompareOp op) {
  return kWindows[size_t(format)][format == DepthFormat::None ? size_t(CompareOp::Always) : size_t(op)];
}

}  // namespace rastercmp::cpu::fast
