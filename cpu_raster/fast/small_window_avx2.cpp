// The window compositor (small_window.hpp) on AVX2 hosts: eight pixels of one window row per step.
// small_window_avx512.cpp's loop on half its width: the same per-pixel formula (tile_kernel.hpp)
// and compare (depth_test_passes) through avx2_depth.hpp's operations, the passing pixels merged
// into the window by blends, lane by lane in primitive order.
#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstdint>

#include "cpu_raster/fast/avx2_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"
#include "cpu_raster/fast/small_window.hpp"
#include "cpu_raster/fast/small_window_lanes.hpp"

namespace rastercmp::cpu::fast {
namespace {

constexpr int kUnit = 8;  // pixels per step: window row r's unit c is columns 8c..8c+7
static_assert(kWindowWidth % kUnit == 0);

// The attachments' window, a row of units per window row; 32-byte aligned, so that a lane's
// store of a unit is forwarded whole to the next lane's load of it.
struct Window {
  alignas(32) uint32_t owner[kWindowHeight][kWindowWidth];
  alignas(32) uint32_t depth[kWindowHeight][kWindowWidth];
};

RASTERCMP_AVX2 inline __m256i load_unit(const uint32_t* p) {
  return _mm256_load_si256(reinterpret_cast<const __m256i*>(p));
}
RASTERCMP_AVX2 inline void store_unit(uint32_t* p, __m256i v) { _mm256_store_si256(reinterpret_cast<__m256i*>(p), v); }

// Row r of the window from the attachment row at `image` (its column grid_x0) and back: the
// units before the last whole, and the last one whole too where its columns past the window lie
// in the tile of the window's last column (`whole_last`: this worker's, as the window's pixels
// there are, and inside the row), else masked to the window's columns (the attachment's pixels
// past them may be another worker's). A whole unit stores back, unchanged, the pixels past the
// window it loaded (no lane covers them); vpmaskmovd's store is slow on the Zen 5 host measured
// (grid_180k with the AVX2 kernels 8-9% faster without it, performance-log.md). Written out for
// the at most four units of a row: a loop of whole units is turned into a call to memmove.
static_assert(kWindowWidth / kUnit == 4);
RASTERCMP_AVX2 inline void copy_in(const uint32_t* image, uint32_t* row, int c) {
  store_unit(row + kUnit * c, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(image + kUnit * c)));
}
RASTERCMP_AVX2 inline void copy_out(const uint32_t* row, uint32_t* image, int c) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(image + kUnit * c), load_unit(row + kUnit * c));
}

RASTERCMP_AVX2 inline void load_row(const uint32_t* image, int units, __m256i last, bool whole_last, uint32_t* row) {
  if (units > 1) copy_in(image, row, 0);
  if (units > 2) copy_in(image, row, 1);
  if (units > 3) copy_in(image, row, 2);
  const int c = units - 1;
  if (whole_last)
    copy_in(image, row, c);
  else
    store_unit(row + kUnit * c, _mm256_maskload_epi32(reinterpret_cast<const int*>(image + kUnit * c), last));
}

RASTERCMP_AVX2 inline void store_row(const uint32_t* row, int units, __m256i last, bool whole_last, uint32_t* image) {
  if (units > 1) copy_out(row, image, 0);
  if (units > 2) copy_out(row, image, 1);
  if (units > 3) copy_out(row, image, 2);
  const int c = units - 1;
  if (whole_last)
    copy_out(row, image, c);
  else
    _mm256_maskstore_epi32(reinterpret_cast<int*>(image + kUnit * c), last, load_unit(row + kUnit * c));
}

// Rows [row_lo, row_hi] lie in the block's union and are the caller's. A lane is evaluated over
// its rows within them and the units of its columns; a unit's pixels outside the lane's bounding
// box are never covered by it (the box holds every sample inside the triangle; the edge values
// are exact over the window, small_triangles.hpp), and those past the window's columns are never
// stored back.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 void composite(const SmallBlockOutput& b, uint32_t owner_of_lane_0, int32_t row_lo, int32_t row_hi,
                              const KernelDepth& kernel, const TileTarget& t) {
  constexpr bool kDepth = F != DepthFormat::None;
  // the draw's depth state in registers: the window's stores could alias a KernelDepth
  const bool fma = kernel.fma, clamp = kernel.clamp, write = kernel.write;
  const __m256 zmin = _mm256_set1_ps(kernel.zmin), zmax = _mm256_set1_ps(kernel.zmax);
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  const int32_t wx0 = b.grid_x0, width = b.grid_x1 - wx0 + 1, height = row_hi - row_lo + 1;
  const int units = (width + kUnit - 1) / kUnit;  // <= kWindowWidth / kUnit
  const __m256i column_of = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i last = _mm256_cmpgt_epi32(_mm256_set1_epi32(width - kUnit * (units - 1)), column_of);
  const size_t pitch = size_t(t.width);
  const int32_t unit_end = wx0 + kUnit * units - 1, window_end = wx0 + width - 1;
  const bool whole_last = unit_end < t.width && unit_end >> kTileOrder == window_end >> kTileOrder;
  Window w;
  for (int r = 0; r < height; ++r) {
    const size_t i = size_t(row_lo + r) * pitch + size_t(wx0);
    load_row(t.owner + i, units, last, whole_last, w.owner[r]);
    if constexpr (kDepth) load_row(t.depth + i, units, last, whole_last, w.depth[r]);
  }
  const __m256 px0 = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(wx0), column_of));  // exact: < 2^24
  const LaneStarts starts = lane_starts<0>(b, row_lo, row_hi);                                 // units of one row
  static_assert(kUnit == 1 << kLaneUnitColumnsLog2);
  for (uint32_t lanes = starts.lanes; lanes != 0; lanes &= lanes - 1) {
    const int l = std::countr_zero(lanes);
    const int32_t y_first = row_lo + starts.first_unit_row[l], y_last = row_lo + starts.last_unit_row[l];
    const int c_first = starts.first_column[l], c_last = starts.last_column[l];
    const __m256i owner = _mm256_set1_epi32(int32_t(owner_of_lane_0 + uint32_t(l)));
    __m256i e0[3], gy[3], gx8[3];
    for (int k = 0; k < 3; ++k) {
      const __m256i gx = _mm256_set1_epi32(b.gx[k][l]);
      e0[k] = _mm256_add_epi32(_mm256_set1_epi32(starts.e[k][l]), _mm256_mullo_epi32(column_of, gx));
      gy[k] = _mm256_set1_epi32(b.gy[k][l]);
      gx8[k] = _mm256_slli_epi32(gx, 3);
    }
    const __m256 a0 = _mm256_set1_ps(b.a0[l]), dzdx = _mm256_set1_ps(b.dzdx[l]), dzdy = _mm256_set1_ps(b.dzdy[l]);
    const __m256 py0 = _mm256_set1_ps(starts.first_y[l]);
    for (int c = c_first;; ++c) {
      const __m256 px = _mm256_add_ps(px0, _mm256_set1_ps(float(kUnit * c)));  // exact
      const __m256 inner = kDepth ? mul_add8(dzdx, px, a0, fma) : __m256{};     // FMA?(dzdx, px, a0)
      __m256 py = py0;
      __m256i e[3] = {e0[0], e0[1], e0[2]};
      for (int32_t y = y_first; y <= y_last; ++y) {
        const int r = y - row_lo;
        // covered: every E - 1 >= 0, i.e. the sign bit of e0 | e1 | e2 clear
        const __m256i covered = _mm256_cmpgt_epi32(_mm256_or_si256(_mm256_or_si256(e[0], e[1]), e[2]),
                                                   _mm256_set1_epi32(-1));
        __m256i pass = covered;
        if constexpr (kDepth && Op == CompareOp::Never) {
          pass = _mm256_setzero_si256();
        } else if constexpr (kDepth && Op != CompareOp::Always) {
          // finish_depth8 without its + o (o = 0: small_triangles.hpp's blocks have no depth bias,
          // and the add changes only -0, which max(min(z, 1), +0) turns into +0 as it would)
          __m256 z = _mm256_max_ps(_mm256_min_ps(mul_add8(dzdy, py, inner, fma), one), zero);
          if (clamp) z = _mm256_max_ps(_mm256_min_ps(z, zmax), zmin);
          const __m256i raw = to_raw<F>(z);
          uint32_t* unit = &w.depth[r][kUnit * c];
          const __m256i stored = load_unit(unit);
          pass = _mm256_and_si256(covered, depth_passes<F, Op>(z, raw, stored));
          if (write) store_unit(unit, _mm256_blendv_epi8(stored, raw, pass));
        } else if constexpr (kDepth) {  // Always: every covered pixel
          __m256 z = _mm256_max_ps(_mm256_min_ps(mul_add8(dzdy, py, inner, fma), one), zero);
          if (clamp) z = _mm256_max_ps(_mm256_min_ps(z, zmax), zmin);
          uint32_t* unit = &w.depth[r][kUnit * c];
          if (write) store_unit(unit, _mm256_blendv_epi8(load_unit(unit), to_raw<F>(z), pass));
        }
        uint32_t* owners = &w.owner[r][kUnit * c];
        store_unit(owners, _mm256_blendv_epi8(load_unit(owners), owner, pass));
        for (int k = 0; k < 3; ++k) e[k] = _mm256_add_epi32(e[k], gy[k]);
        py = _mm256_add_ps(py, one);
      }
      if (c == c_last) break;
      for (int k = 0; k < 3; ++k) e0[k] = _mm256_add_epi32(e0[k], gx8[k]);
    }
  }
  for (int r = 0; r < height; ++r) {
    const size_t i = size_t(row_lo + r) * pitch + size_t(wx0);
    store_row(w.owner[r], units, last, whole_last, t.owner + i);
    if (kDepth && write) store_row(w.depth[r], units, last, whole_last, t.depth + i);
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

WindowBlockFn select_window_block_avx2(DepthFormat format, CompareOp op) { return select_kernel(kWindows, format, op); }

}  // namespace rastercmp::cpu::fast
