#include "cpu_raster/fast/block_rows.hpp"

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <climits>

#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/fast_frame.hpp"

namespace rastercmp::cpu::fast {
namespace {

// Horizontal minimum and maximum of eight 32-bit lanes, unsigned or signed.
RASTERCMP_AVX2 inline uint32_t min_epu32_of(__m256i v) {
  v = _mm256_min_epu32(v, _mm256_permute2x128_si256(v, v, 0x01));
  v = _mm256_min_epu32(v, _mm256_shuffle_epi32(v, 0x4E));
  return uint32_t(_mm256_cvtsi256_si32(_mm256_min_epu32(v, _mm256_shuffle_epi32(v, 0xB1))));
}
RASTERCMP_AVX2 inline uint32_t max_epu32_of(__m256i v) {
  v = _mm256_max_epu32(v, _mm256_permute2x128_si256(v, v, 0x01));
  v = _mm256_max_epu32(v, _mm256_shuffle_epi32(v, 0x4E));
  return uint32_t(_mm256_cvtsi256_si32(_mm256_max_epu32(v, _mm256_shuffle_epi32(v, 0xB1))));
}

// The smallest and largest of `count` indices (count a multiple of 8).
RASTERCMP_AVX2 void index_span_avx2(const uint32_t* indices, size_t count, uint32_t& smallest, uint32_t& largest) {
  __m256i lo = _mm256_set1_epi32(-1), hi = _mm256_setzero_si256();
  for (size_t i = 0; i < count; i += 8) {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(indices + i));
    lo = _mm256_min_epu32(lo, v);
    hi = _mm256_max_epu32(hi, v);
  }
  smallest = min_epu32_of(lo);
  largest = max_epu32_of(hi);
}

// The lowest and highest of tile_rows[first..last] (unknown rows are the lowest), and the clip bits
// every one of them holds (row_clip_bits; none as soon as one row is known).
RASTERCMP_AVX2 void row_span_avx2(const int16_t* tile_rows, uint32_t first, uint32_t last, int32_t& lowest,
                                  int32_t& highest, uint32_t& shared_clip_bits) {
  __m256i lo = _mm256_set1_epi16(INT16_MAX), hi = _mm256_set1_epi16(INT16_MIN);
  __m256i shared = _mm256_set1_epi16(int16_t(kVertexClipBits));
  const __m256i last_unknown = _mm256_set1_epi16(int16_t(kLastUnknownRow));
  uint32_t i = first;
  for (; i + 16 <= last + 1; i += 16) {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(tile_rows + i));
    lo = _mm256_min_epi16(lo, v);
    hi = _mm256_max_epi16(hi, v);
    shared = _mm256_and_si256(shared, _mm256_andnot_si256(_mm256_cmpgt_epi16(v, last_unknown), v));
  }
  // sixteen signed 16-bit lanes to eight 32-bit ones (sign-extended halves), then as above with
  // a bias that makes signed order unsigned
  const __m256i bias = _mm256_set1_epi32(INT32_MIN);
  const __m256i lo32 = _mm256_min_epi32(_mm256_srai_epi32(_mm256_slli_epi32(lo, 16), 16), _mm256_srai_epi32(lo, 16));
  const __m256i hi32 = _mm256_max_epi32(_mm256_srai_epi32(_mm256_slli_epi32(hi, 16), 16), _mm256_srai_epi32(hi, 16));
  lowest = int32_t(min_epu32_of(_mm256_xor_si256(lo32, bias)) ^ uint32_t(INT32_MIN));
  highest = int32_t(max_epu32_of(_mm256_xor_si256(hi32, bias)) ^ uint32_t(INT32_MIN));
  alignas(32) uint16_t lanes[16];
  _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), shared);
  shared_clip_bits = kVertexClipBits;
  for (const uint16_t bits : lanes) shared_clip_bits &= bits;
  for (; i <= last; ++i) {
    lowest = std::min(lowest, int32_t(tile_rows[i]));
    highest = std::max(highest, int32_t(tile_rows[i]));
    shared_clip_bits &= row_clip_bits(tile_rows[i]);
  }
}

}  // namespace

// Tile rows lo..hi cut to the draw region's, packed lo | hi << 16 (lo > hi: none).
uint32_t pack_rows(int32_t lo, int32_t hi, const PixelRect& region) {
  lo = std::max(lo, region.y0 >> kTileOrder);  // the corner rows bound the bounding boxes' rows
  hi = std::min(hi, region.y1 >> kTileOrder);
  if (lo > hi) return kNoRow;
  return uint32_t(lo) | uint32_t(hi) << 16;
}

// The tile rows a block's triangles may reach, from the corners' tile rows (fast_vertices.hpp):
// the bounding boxes lie within them. kBlockAnyRow when a corner needs clipping or failed to snap
// (its window position says nothing then), or names no position (`bad` is set then).
uint32_t block_tile_rows(const SmallBlockInput& in, const int16_t* tile_rows, uint32_t positions,
                         const PixelRect& region, bool& bad) {
  int32_t lo = INT32_MAX, hi = INT32_MIN;
  for (uint32_t l = 0; l < in.count; ++l) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t position = in.corners[k][l * in.stride];
      if (position >= positions) {
        bad = true;
        return kBlockAnyRow;
      }
      const int16_t row = tile_rows[position];
      if (is_unknown_row(row)) return kBlockAnyRow;
      lo = std::min(lo, int32_t(row));
      hi = std::max(hi, int32_t(row));
    }
  }
  return pack_rows(lo, hi, region);
}

// block_tile_rows for a full block of an indexed list: its 24 corners are consecutive in the
// index buffer; three AVX2 gathers of 32 bits at 2-byte steps fetch their rows (each row is the
// low half; the last position's read reaches 2 bytes into the scratch's padding,
// thread_row_scratch). Unknown rows lie below every known row, so the minimum finds them; their
// low bits hold the corners' clip bits (unknown_row), which the "outside one plane" test ANDs per
// lane. The indices are checked against `positions` (> 0) before any gather.
RASTERCMP_AVX2 uint32_t list_block_tile_rows_avx2(const uint32_t* indices, const int16_t* tile_rows,
                                                  uint32_t positions, const PixelRect& region, bool& bad) {
  __m256i idx[3];
  for (int j = 0; j < 3; ++j) idx[j] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(indices + 8 * j));
  const __m256i largest = _mm256_max_epu32(idx[0], _mm256_max_epu32(idx[1], idx[2]));
  const __m256i last = _mm256_set1_epi32(int32_t(positions - 1));
  if (!_mm256_testc_si256(_mm256_cmpeq_epi32(_mm256_max_epu32(largest, last), last), _mm256_set1_epi32(-1))) {
    bad = true;  // some index > positions - 1
    return kBlockAnyRow;
  }
  const int* base = reinterpret_cast<const int*>(tile_rows);
  __m256i r[3];
  for (int j = 0; j < 3; ++j) {
    const __m256i word = _mm256_i32gather_epi32(base, idx[j], 2);
    r[j] = _mm256_srai_epi32(_mm256_slli_epi32(word, 16), 16);
  }
  __m256i lo = _mm256_min_epi32(r[0], _mm256_min_epi32(r[1], r[2]));
  __m256i hi = _mm256_max_epi32(r[0], _mm256_max_epi32(r[1], r[2]));
  lo = _mm256_min_epi32(lo, _mm256_permute2x128_si256(lo, lo, 0x01));
  hi = _mm256_max_epi32(hi, _mm256_permute2x128_si256(hi, hi, 0x01));
  lo = _mm256_min_epi32(lo, _mm256_shuffle_epi32(lo, 0x4E));
  hi = _mm256_max_epi32(hi, _mm256_shuffle_epi32(hi, 0x4E));
  lo = _mm256_min_epi32(lo, _mm256_shuffle_epi32(lo, 0xB1));
  hi = _mm256_max_epi32(hi, _mm256_shuffle_epi32(hi, 0xB1));
  const int32_t low = _mm256_cvtsi256_si32(lo), high = _mm256_cvtsi256_si32(hi);
  if (!is_unknown_row(low)) return pack_rows(low, high, region);
  // A corner needs clipping (or failed to snap): the clip bits the three corners of each lane
  // share (row_clip_bits: an unknown row's low bits, none for a known row).
  const __m256i last_unknown = _mm256_set1_epi32(kLastUnknownRow);
  __m256i shared = _mm256_set1_epi32(int32_t(kVertexClipBits));
  for (int j = 0; j < 3; ++j)
    shared = _mm256_and_si256(shared, _mm256_andnot_si256(_mm256_cmpgt_epi32(r[j], last_unknown), r[j]));
  const bool every_lane_outside = _mm256_testz_si256(_mm256_cmpeq_epi32(shared, _mm256_setzero_si256()),
                                                     _mm256_set1_epi32(-1));
  return every_lane_outside ? kNoRow : kBlockAnyRow;
}

// Taken when the indices lie in a short range of positions (a mesh's neighbourhood) and either
// every position in it has a known row, and those rows are one tile row, or none of them is in the
// region; or every position in it is outside one clip plane (a camera's mesh behind it or past the
// far plane). Why that is each block's own answer: a block's corners are among the range's
// positions, so its rows (known, not empty) lie within the range's: the same one row, or none in
// the region either; or every lane has its three corners outside that plane (kNoRow, as
// list_block_tile_rows_avx2 finds). (A range that only its cut makes one row is declined: a block
// of it may lie outside the region.) Out-of-range indices are left to the block-by-block
// measurement, which reports them.
RASTERCMP_AVX2 bool span_tile_rows_avx2(const uint32_t* indices, uint32_t n, const int16_t* tile_rows,
                                        uint32_t positions, const PixelRect& region, uint32_t* block_rows) {
  uint32_t smallest = 0, largest = 0;
  index_span_avx2(indices, 24 * size_t(n), smallest, largest);
  if (largest >= positions || largest - smallest >= kSpanPositions) return false;
  int32_t lowest = 0, highest = 0;
  uint32_t outside = 0;
  row_span_avx2(tile_rows, smallest, largest, lowest, highest, outside);
  if (outside != 0) {
    std::fill_n(block_rows, n, kNoRow);
    return true;
  }
  if (is_unknown_row(lowest)) return false;
  const uint32_t rows = pack_rows(lowest, highest, region);
  if (lowest != highest && rows != kNoRow) return false;  // several tile rows: the blocks may differ
  std::fill_n(block_rows, n, rows);
  return true;
}

RASTERCMP_AVX2 uint32_t next_reaching_block_avx2(const uint32_t* block_rows, uint32_t begin, uint32_t end) {
  const __m256i none = _mm256_set1_epi32(int32_t(kNoRow));
  uint32_t b = begin;
  for (; b + 8 <= end; b += 8) {
    const __m256i rows = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(block_rows + b));
    const uint32_t reaching =
        ~uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(rows, none)))) & 0xFFu;
    if (reaching != 0) return b + uint32_t(std::countr_zero(reaching));
  }
  while (b < end && block_rows[b] == kNoRow) ++b;
  return b;
}

namespace {
// next_block_in_run_avx2's test of one block.
bool block_in_run(uint32_t rows, uint32_t columns, int32_t tile_y, int32_t first, int32_t last) {
  if (rows == kBlockAnyRow) return true;
  if (int32_t(rows & 0xFFFFu) > tile_y || int32_t(rows >> 16) < tile_y) return false;
  if (columns == kColumnsAny || columns == kColumnsUnknown) return true;
  return int32_t(columns & 0xFFFFu) - 1 <= last && int32_t(columns >> 16) - 1 >= first;
}
}  // namespace

RASTERCMP_AVX2 uint32_t next_block_in_run_avx2(const uint32_t* block_rows, const uint32_t* block_columns,
                                               uint32_t begin, uint32_t end, int32_t tile_y, int32_t first,
                                               int32_t last) {
  const __m256i low = _mm256_set1_epi32(0xFFFF), row = _mm256_set1_epi32(tile_y);
  const __m256i any_row = _mm256_set1_epi32(int32_t(kBlockAnyRow));
  // kColumnsAny and kColumnsUnknown are the two largest values: columns >= kColumnsAny, unsigned
  const __m256i any_columns = _mm256_set1_epi32(int32_t(kColumnsAny));
  // columns x0 + 1 <= last + 1 and x1 + 1 >= first + 1, in the packed halves
  const __m256i last1 = _mm256_set1_epi32(last + 1), first1 = _mm256_set1_epi32(first + 1);
  uint32_t b = begin;
  for (; b + 8 <= end; b += 8) {
    const __m256i rows = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(block_rows + b));
    const __m256i columns = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(block_columns + b));
    const __m256i lo = _mm256_and_si256(rows, low), hi = _mm256_srli_epi32(rows, 16);
    const __m256i outside_rows = _mm256_or_si256(_mm256_cmpgt_epi32(lo, row), _mm256_cmpgt_epi32(row, hi));
    const __m256i c0 = _mm256_and_si256(columns, low), c1 = _mm256_srli_epi32(columns, 16);
    const __m256i outside_columns = _mm256_or_si256(_mm256_cmpgt_epi32(c0, last1), _mm256_cmpgt_epi32(first1, c1));
    const __m256i any = _mm256_cmpeq_epi32(_mm256_max_epu32(columns, any_columns), columns);
    const __m256i miss = _mm256_or_si256(outside_rows, _mm256_andnot_si256(any, outside_columns));
    const uint32_t mask = (~uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(miss))) |
                           uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(rows, any_row))))) &
                          0xFFu;
    if (mask != 0) return b + uint32_t(std::countr_zero(mask));
  }
  while (b < end && !block_in_run(block_rows[b], block_columns[b], tile_y, first, last)) ++b;
  return b;
}

}  // namespace rastercmp::cpu::fast
