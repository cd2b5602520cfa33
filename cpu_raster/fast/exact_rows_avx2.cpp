// The exact rows (exact_rows.hpp) with AVX2, their covered columns from exact_rows_avx2.hpp (the
// plane rows set up in plane_rows_avx2.cpp): in a frame of one sample per pixel (lines) each four
// rows' one or two columns a step (gathered, or read and written as pairs where the rows spread
// over the L1's sets), or a row's run eight contiguous columns a step (thin_rows); fragments queued
// from any row and column and their stored depths gathered (depth_rows: Bresenham lines in 4x
// frames); without an active depth test the owner alone (coverage_rows). Per-sample primitives in
// 4x frames: exact_rows_4x_avx2.cpp.
#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

#include "cpu_raster/fast/avx2_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/exact_rows_avx2.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"
#include "cpu_raster/fast/frame_memory.hpp"

namespace rastercmp::cpu::fast {

namespace {

// Calls run(py, s, x0, x1) for each sample row of rows [y0, y1] with a covered column (its covered
// columns [x0, x1]); false, having called nothing, when the planes leave the exact bounds.
template <class Run>
RASTERCMP_AVX2 bool for_each_run(const RasterPrimitive& p, int32_t y0, int32_t y1, uint32_t tested_samples, Run&& run) {
  PlaneRows planes;
  if (!init_plane_rows(planes, p, tested_samples, y0, y1)) return false;
  const __m256d first = _mm256_set1_pd(double(p.visit.x0)), last = _mm256_set1_pd(double(p.visit.x1));
  alignas(16) int32_t u0[4], u1[4];
  for (uint32_t s = 0; s < tested_samples; ++s) {
    start_sample(planes, s);
    for (int32_t y = y0; y <= y1; y += 4) {
      next_plane_rows(planes, s, first, last, u0, u1);
      const int32_t rows = std::min(4, y1 - y + 1);
      for (int32_t k = 0; k < rows; ++k)
        if (u0[k] <= u1[k]) run(y + k, s, u0[k], u1[k]);
    }
  }
  return true;
}

constexpr int32_t kBatch = 256;

// The covered samples of a primitive waiting for their depth: index into the targets (sample s,
// or 0 for a pixel-centre primitive), and the depth interpolation point.
struct Fragments {
  alignas(32) int32_t index[kBatch + 8];
  alignas(32) float x[kBatch + 8], y[kBatch + 8];
};

// How a step's passing lanes are written: one by one (Lanes), by scatter_passing (Scatter:
// AVX-512 hosts, one owner value a lane), or every valid lane, those that failed with the values
// they held (Blended: one owner value a lane).
enum class StepWrites { Lanes, Scatter, Blended };

// Eight fragments of one primitive, distinct samples anywhere in the targets: `index` (the sample's
// value, or a pixel's first for a pixel-centre primitive) where `valid`, depth at (x, y), the stored
// depths gathered and tested, the passing ones written as `writes` says (the owner to
// `owner_values` values from the index: a pixel-centre primitive's to every sample of the pixel).
struct GatheredStep {
  __m256 a0, dzdx, dzdy, offset;
  uint32_t* depth;
  uint32_t* owner;
  uint32_t id, owner_values;
  StepWrites writes;
};

RASTERCMP_AVX2 inline GatheredStep gathered_step_of(const RasterPrimitive& p, RenderTargets& targets,
                                                    bool avx512_writes) {
  const uint32_t owner_values = p.per_sample ? 1u : targets.samples;
  return GatheredStep{_mm256_set1_ps(p.depth.a0),
                      _mm256_set1_ps(p.depth.dzdx),
                      _mm256_set1_ps(p.depth.dzdy),
                      _mm256_set1_ps(p.offset.offset),
                      targets.depth_raw.data(),
                      targets.owner.data(),
                      p.owner,
                      owner_values,
                      owner_values != 1 ? StepWrites::Lanes
                      : avx512_writes   ? StepWrites::Scatter
                                        : StepWrites::Blended};
}

// The writes of a gathered step's passing lanes (distinct positions `index`) with two masked
// scatters: the raw depths (when written) and the owner. The same stores as draw_gathered's loop
// over the lanes, without a branch per lane that waits on the gathered depths.
RASTERCMP_AVX512 void scatter_passing(const GatheredStep& c, bool write, __m256i index, __m256i pass, __m256i raw) {
  const __mmask8 lanes = _mm256_movepi32_mask(pass);
  if (write) _mm256_mask_i32scatter_epi32(c.depth, lanes, index, raw, 4);
  _mm256_mask_i32scatter_epi32(c.owner, lanes, index, _mm256_set1_epi32(int32_t(c.id)), 4);
}

template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 inline void draw_gathered(const GatheredStep& c, const KernelDepth& d, __m256 x, __m256 y, __m256i index,
                                         __m256i valid) {
  const __m256 z = finish_depth8(mul_add8(c.dzdy, y, mul_add8(c.dzdx, x, c.a0, d.fma), d.fma), c.offset, d);
  const __m256i raw = to_raw<F>(z);
  __m256i pass = valid, stored = raw;
  if constexpr (Op != CompareOp::Always) {
    stored =
        _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(c.depth), index, valid, 4);
    pass = _mm256_and_si256(valid, depth_passes<F, Op>(z, raw, stored));
  }
  if (c.writes == StepWrites::Scatter) {
    scatter_passing(c, d.write, index, pass, raw);
    return;
  }
  if (c.writes == StepWrites::Blended) {
    // A valid lane is a sample of this primitive in this worker's tiles: storing back what a
    // failing one held changes nothing, and no other worker writes it. An invalid lane's stores
    // go to a scratch word. So eight stores of each kind, without a branch on the test.
    const __m256i id = _mm256_set1_epi32(int32_t(c.id));
    __m256i owner_out = id;
    if constexpr (Op != CompareOp::Always)
      owner_out = _mm256_blendv_epi8(
          _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(c.owner), index, valid, 4),
          id, pass);
    alignas(32) uint32_t depth_lanes[8], owner_lanes[8];
    alignas(32) int32_t index_lanes[8], valid_lanes[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(depth_lanes), _mm256_blendv_epi8(stored, raw, pass));
    _mm256_store_si256(reinterpret_cast<__m256i*>(owner_lanes), owner_out);
    _mm256_store_si256(reinterpret_cast<__m256i*>(index_lanes), index);
    _mm256_store_si256(reinterpret_cast<__m256i*>(valid_lanes), valid);
    uint32_t scratch[2];
    for (uint32_t k = 0; k < 8; ++k) {
      const bool in = valid_lanes[k] != 0;
      const size_t at = in ? size_t(uint32_t(index_lanes[k])) : 0;
      uint32_t* depth_at = in ? c.depth + at : scratch;
      uint32_t* owner_at = in ? c.owner + at : scratch + 1;
      if (d.write) *depth_at = depth_lanes[k];
      *owner_at = owner_lanes[k];
    }
    return;
  }
  uint32_t bits = uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(pass)));
  if (bits == 0) return;
  alignas(32) uint32_t raw_lanes[8];
  alignas(32) int32_t index_lanes[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(raw_lanes), raw);
  _mm256_store_si256(reinterpret_cast<__m256i*>(index_lanes), index);
  for (; bits != 0; bits &= bits - 1) {
    const int k = std::countr_zero(bits);
    const size_t at = size_t(uint32_t(index_lanes[k]));
    if (d.write) c.depth[at] = raw_lanes[k];
    for (uint32_t t = 0; t < c.owner_values; ++t) c.owner[at + t] = c.id;
  }
}

// Four pairs' two words each as one 64-bit lane (memcpy: a pair need not be aligned), lane by lane:
// one 32-byte load of four 8-byte stores would wait for them to retire.
RASTERCMP_AVX2 inline __m256i pairs_of(uint32_t* const* pair) {
  int64_t v[4];
  for (int k = 0; k < 4; ++k) std::memcpy(&v[k], pair[k], sizeof(int64_t));
  return _mm256_setr_epi64x(v[0], v[1], v[2], v[3]);
}

// A gathered step of thin_rows (lane 2k + j: row k, column u0[k] + j) with each row's two pixels
// read and written as one 64-bit word of each attachment, in a frame whose rows spread over the
// L1's sets (rows_share_l1_sets false: there plain loads and stores beat the gather and scatters,
// which suffer less where the rows share a set; rastercmp_bench_access). `at[k]`: row k's first
// pixel, `live[k]`: its run is not empty. Every pixel of a live row's pair is in this worker's
// tiles (the caller checks u0[k] + 1 against the last column it owns: the visit's, or in whole
// rows owned_row_end), so the step writes back, unchanged, what a lane that is not covered or fails
// held (no other worker writes it), as the blended writes do; an empty row's words go to a scratch
// pair.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 inline void draw_pairs(const GatheredStep& c, const KernelDepth& d, __m256 x, __m256 y, __m256i valid,
                                      const int32_t* at, const int32_t* live) {
  uint32_t scratch[4];
  uint32_t* depth_pair[4];
  uint32_t* owner_pair[4];
  for (int k = 0; k < 4; ++k) {
    depth_pair[k] = live[k] != 0 ? c.depth + at[k] : scratch;
    owner_pair[k] = live[k] != 0 ? c.owner + at[k] : scratch + 2;
  }
  const __m256i stored = pairs_of(depth_pair), held = pairs_of(owner_pair);
  const __m256 z = finish_depth8(mul_add8(c.dzdy, y, mul_add8(c.dzdx, x, c.a0, d.fma), d.fma), c.offset, d);
  const __m256i raw = to_raw<F>(z);
  __m256i pass = valid;
  if constexpr (Op != CompareOp::Always) pass = _mm256_and_si256(valid, depth_passes<F, Op>(z, raw, stored));
  alignas(32) uint64_t depth_out[4], owner_out[4];
  _mm256_store_si256(reinterpret_cast<__m256i*>(depth_out), _mm256_blendv_epi8(stored, raw, pass));
  _mm256_store_si256(reinterpret_cast<__m256i*>(owner_out),
                     _mm256_blendv_epi8(held, _mm256_set1_epi32(int32_t(c.id)), pass));
  for (int k = 0; k < 4; ++k) {
    if (d.write) std::memcpy(depth_pair[k], &depth_out[k], sizeof(uint64_t));
    std::memcpy(owner_pair[k], &owner_out[k], sizeof(uint64_t));
  }
}

// Fragments [0, count): raw depth, test against the stored values, writes.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 void flush_fragments(const Fragments& f, int32_t count, const RasterPrimitive& p, const KernelDepth& d,
                                    RenderTargets& targets) {
  const GatheredStep step = gathered_step_of(p, targets, false);  // four owner values a fragment
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (int32_t i = 0; i < count; i += 8)
    draw_gathered<F, Op>(step, d, _mm256_load_ps(f.x + i), _mm256_load_ps(f.y + i),
                         _mm256_load_si256(reinterpret_cast<const __m256i*>(f.index + i)),
                         _mm256_cmpgt_epi32(_mm256_set1_epi32(count - i), lanes));
}

// With an active depth test: each covered run of a sample row queued (index, x and y of each
// column, eight at a time), its depth and owner lines prefetched (they are read and written when
// the batch is flushed; a line's rows lie in different lines of the attachments), and the batch
// flushed when full and at the end.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool depth_rows(const RasterPrimitive& p, int32_t y0, int32_t y1, const KernelDepth& d,
                               RenderTargets& targets) {
  const uint32_t tested = p.per_sample ? targets.samples : 1;
  PlaneRows planes;
  if (!init_plane_rows(planes, p, tested, y0, y1)) return false;
  Fragments f;  // written before read
  int32_t count = 0;
  const int32_t stride = int32_t(targets.samples), row_stride = int32_t(targets.width) * stride;
  const uint32_t* depth = targets.depth_raw.data();
  const uint32_t* owner = targets.owner.data();
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), column_step = _mm256_set1_epi32(stride);
  const __m256d first = _mm256_set1_pd(double(p.visit.x0)), last = _mm256_set1_pd(double(p.visit.x1));
  alignas(16) int32_t u0[4], u1[4];
  for (uint32_t s = 0; s < tested; ++s) {
    start_sample(planes, s);
    // sample_point's floats: float(px) and float(py) plus the sample's offsets; a pixel-centre
    // primitive adds +0 to x, which leaves an integer-valued float (never -0) unchanged
    const float sx = p.per_sample ? kStandardSamples4x[s].x : 0.0f;
    const __m256 x_offset = _mm256_set1_ps(sx);
    const int32_t sample = p.per_sample ? int32_t(s) : 0;
    const float sy = p.per_sample ? kStandardSamples4x[s].y : 0.0f;
    for (int32_t y = y0; y <= y1; y += 4) {
      next_plane_rows(planes, s, first, last, u0, u1);
      const int32_t rows = std::min(4, y1 - y + 1);
      // A thin primitive's four rows, each run at most eight columns: every row's eight lanes
      // stored at the end of the queue so far (an empty row's lanes, past it, are overwritten
      // by the next row's or lie past the queue's end), without a branch on the runs.
      const __m128i runs = _mm_max_epi32(
          _mm_sub_epi32(_mm_load_si128(reinterpret_cast<const __m128i*>(u1)),
                        _mm_sub_epi32(_mm_load_si128(reinterpret_cast<const __m128i*>(u0)), _mm_set1_epi32(1))),
          _mm_setzero_si128());
      if (rows == 4 && count <= kBatch - 32 &&
          _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(runs, _mm_set1_epi32(8)))) == 0) {
        alignas(16) int32_t length[4];
        _mm_store_si128(reinterpret_cast<__m128i*>(length), runs);
        for (int32_t k = 0; k < 4; ++k) {
          const int32_t py = y + k, x0 = u0[k], base = py * row_stride + sample;  // targets.index(0, py, sample)
          const float fy = p.per_sample ? float(py) + sy : float(py);
          const __m256i px = _mm256_add_epi32(_mm256_set1_epi32(x0), lanes);
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(f.index + count),
                              _mm256_add_epi32(_mm256_set1_epi32(base), _mm256_mullo_epi32(px, column_step)));
          _mm256_storeu_ps(f.x + count, _mm256_add_ps(_mm256_cvtepi32_ps(px), x_offset));
          _mm256_storeu_ps(f.y + count, _mm256_set1_ps(fy));
          if (length[k] > 0) {
            _mm_prefetch(reinterpret_cast<const char*>(depth + base + x0 * stride), _MM_HINT_T0);
            _mm_prefetch(reinterpret_cast<const char*>(owner + base + x0 * stride), _MM_HINT_T0);
          }
          count += length[k];
        }
        continue;
      }
      for (int32_t k = 0; k < rows; ++k) {
        const int32_t x0 = u0[k], x1 = u1[k];
        if (x0 > x1) continue;
        const int32_t py = y + k, base = py * row_stride + sample;  // targets.index(0, py, sample)
        const float fy = p.per_sample ? float(py) + sy : float(py);
        const int32_t at0 = base + x0 * stride, at1 = base + x1 * stride;
        _mm_prefetch(reinterpret_cast<const char*>(depth + at0), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(owner + at0), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(depth + at1), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(owner + at1), _MM_HINT_T0);
        const __m256i base_v = _mm256_set1_epi32(base);
        const __m256 y_v = _mm256_set1_ps(fy);
        for (int32_t x = x0; x <= x1; x += 8) {
          if (count > kBatch - 8) {
            flush_fragments<F, Op>(f, count, p, d, targets);
            count = 0;
          }
          const __m256i px = _mm256_add_epi32(_mm256_set1_epi32(x), lanes);
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(f.index + count),
                              _mm256_add_epi32(base_v, _mm256_mullo_epi32(px, column_step)));
          _mm256_storeu_ps(f.x + count, _mm256_add_ps(_mm256_cvtepi32_ps(px), x_offset));
          _mm256_storeu_ps(f.y + count, y_v);
          count += std::min(8, x1 - x + 1);
        }
      }
    }
  }
  flush_fragments<F, Op>(f, count, p, d, targets);
  return true;
}

// Four rows' depth and owner lines at word offsets `at`, for reading: Locality 3 into the L1
// (prefetcht0), 2 into the L2 (prefetcht1).
template <int Locality>
RASTERCMP_AVX2 inline void prefetch_rows(uintptr_t depth_bytes, uintptr_t owner_bytes, const uint32_t* at) {
  for (int32_t k = 0; k < 4; ++k) {
    __builtin_prefetch(reinterpret_cast<const char*>(depth_bytes + size_t(at[k]) * 4), 0, Locality);
    __builtin_prefetch(reinterpret_cast<const char*>(owner_bytes + size_t(at[k]) * 4), 0, Locality);
  }
}

// With an active depth test, a primitive in a frame of one sample per pixel (lines, mostly): the
// columns of up to kChunkRows rows worked out (between a line's caps from its long edges alone:
// parallelogram_middle) and each row's depth and owner lines asked for, then per step of four rows
// either one gathered eight-lane step, when every row's run is at most two columns (lane 2k + j:
// row k, column u0[k] + j, valid when j < the run), or, row by row, steps of eight contiguous
// columns masked to the run (a row of one sample per pixel is contiguous in the attachments; a step
// whose eight columns are all the worker's, in the visit or in the row up to owned_row_end, read
// and written whole, the others masked). Each lane's depth, test and write are draw_gathered's (the
// gathered step's writes scattered on AVX-512 hosts, blended elsewhere: StepWrites), or where the
// frame's rows spread over the L1's sets draw_pairs' (each row's two pixels one 64-bit word); a
// step holds distinct samples of one primitive, so reading its stored values before writing any
// reads what the exact path's order reads. Without the queue of depth_rows: a thin line's fragment
// is drawn where its row's columns are known.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool thin_rows(const RasterPrimitive& p, int32_t y0, int32_t y1, const KernelDepth& d,
                              RenderTargets& targets, bool avx512_writes, int32_t owned_row_end) {
  PlaneRows planes;
  if (!init_plane_rows(planes, p, 1, y0, y1)) return false;
  start_sample(planes, 0);
  // a line's rows between its caps: the columns from its long edges alone
  const ParallelogramMiddle middle =
      y1 - y0 + 1 >= kMiddleMinRows ? parallelogram_middle(p, planes) : ParallelogramMiddle{};
  const int32_t width = int32_t(targets.width);
  const GatheredStep gathered = gathered_step_of(p, targets, avx512_writes);
  uint32_t* depth = gathered.depth;
  uint32_t* owner = gathered.owner;
  const __m256i id = _mm256_set1_epi32(int32_t(p.owner));
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i lane_row = _mm256_setr_epi32(0, 0, 1, 1, 2, 2, 3, 3),
                lane_column = _mm256_setr_epi32(0, 1, 0, 1, 0, 1, 0, 1);
  const __m256d first = _mm256_set1_pd(double(p.visit.x0)), last = _mm256_set1_pd(double(p.visit.x1));
  const uintptr_t depth_bytes = reinterpret_cast<uintptr_t>(depth), owner_bytes = reinterpret_cast<uintptr_t>(owner);
  const __m128i row_lanes = _mm_setr_epi32(0, 1, 2, 3), width4 = _mm_set1_epi32(width);
  const __m128i last_column = _mm_set1_epi32(p.visit.x1), one4 = _mm_set1_epi32(1);
  // the last column a step may read and write back: the visit's, or the worker's in its rows
  const int32_t last_owned = std::max(p.visit.x1, owned_row_end);
  const __m128i last_owned4 = _mm_set1_epi32(last_owned);
  // the gathered steps as 64-bit pairs where the rows spread over the L1's sets (draw_pairs)
  const bool pairs = !rows_share_l1_sets(size_t(width) * sizeof(uint32_t));
  constexpr int32_t kChunkRows = 64;
  alignas(16) int32_t u[kChunkRows / 4][2][4];  // [step][lo, hi][row of the step]
  for (int32_t chunk = y0; chunk <= y1; chunk += kChunkRows) {
    const int32_t chunk_end = std::min(y1, chunk + kChunkRows - 1);
    for (int32_t y = chunk, b = 0; y <= chunk_end; y += 4, ++b) {
      if (y >= middle.first_row && y <= middle.last_row - 3)
        next_middle_rows(planes, middle, 0, first, last, u[b][0], u[b][1]);
      else
        next_plane_rows(planes, 0, first, last, u[b][0], u[b][1]);
      // each of the four rows' first column, without a branch on empty rows or rows past the
      // chunk (their lines are asked for all the same; a prefetch never faults, so the address,
      // formed as an integer, may lie past the attachments): into the L1 where the frame's rows
      // spread over its sets (the chunk's 128 lines take 8 KiB of it), else into the L2: in a
      // frame 1,024 px wide a steep line's rows, 4 KiB apart, fall in one set of the L1 (12
      // ways), where the chunk's 64 would evict one another
      alignas(16) uint32_t at[4];
      const __m128i row4 = _mm_add_epi32(_mm_set1_epi32(y), row_lanes);
      const __m128i column4 = _mm_min_epi32(_mm_load_si128(reinterpret_cast<const __m128i*>(u[b][0])), last_column);
      _mm_store_si128(reinterpret_cast<__m128i*>(at), _mm_add_epi32(_mm_mullo_epi32(row4, width4), column4));
      if (pairs)
        prefetch_rows<3>(depth_bytes, owner_bytes, at);
      else
        prefetch_rows<2>(depth_bytes, owner_bytes, at);
    }
    for (int32_t y = chunk, b = 0; y <= chunk_end; y += 4, ++b) {
      const int32_t rows = std::min(4, chunk_end - y + 1);
      // rows past the chunk's end are made empty (their columns were computed, never to be drawn)
      const __m128i row_valid = _mm_cmpgt_epi32(_mm_set1_epi32(rows), _mm_setr_epi32(0, 1, 2, 3));
      const __m128i lo = _mm_load_si128(reinterpret_cast<const __m128i*>(u[b][0]));
      const __m128i runs = _mm_and_si128(
          row_valid, _mm_max_epi32(_mm_sub_epi32(_mm_load_si128(reinterpret_cast<const __m128i*>(u[b][1])),
                                                 _mm_sub_epi32(lo, _mm_set1_epi32(1))),
                                   _mm_setzero_si128()));
      if (_mm_testz_si128(runs, runs)) continue;
      if (_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(runs, _mm_set1_epi32(2)))) == 0) {
        // every run at most two columns: one gathered step
        const __m256i row = _mm256_add_epi32(_mm256_set1_epi32(y), lane_row);
        const __m256i column =
            _mm256_add_epi32(_mm256_permutevar8x32_epi32(_mm256_castsi128_si256(lo), lane_row), lane_column);
        const __m256i valid =
            _mm256_cmpgt_epi32(_mm256_permutevar8x32_epi32(_mm256_castsi128_si256(runs), lane_row), lane_column);
        // sample_point's floats for a pixel-centre sample: float(px), float(py)
        const __m256 x = _mm256_cvtepi32_ps(column), y_lanes = _mm256_cvtepi32_ps(row);
        const __m128i live = _mm_cmpgt_epi32(runs, _mm_setzero_si128());
        // pairs where every live row's second pixel is this worker's (a run of one at the last
        // column it owns not)
        const __m128i short_at_end = _mm_and_si128(live, _mm_cmpgt_epi32(lo, _mm_sub_epi32(last_owned4, one4)));
        if (pairs && _mm_testz_si128(short_at_end, short_at_end)) {
          alignas(16) int32_t at[4], live_rows[4];
          _mm_store_si128(reinterpret_cast<__m128i*>(at),
                          _mm_add_epi32(_mm_mullo_epi32(_mm_add_epi32(_mm_set1_epi32(y), row_lanes), width4), lo));
          _mm_store_si128(reinterpret_cast<__m128i*>(live_rows), live);
          draw_pairs<F, Op>(gathered, d, x, y_lanes, valid, at, live_rows);
          continue;
        }
        const __m256i index = _mm256_add_epi32(_mm256_mullo_epi32(row, _mm256_set1_epi32(width)), column);
        draw_gathered<F, Op>(gathered, d, x, y_lanes, index, valid);
        continue;
      }
      for (int32_t k = 0; k < rows; ++k) {
        const int32_t x0 = u[b][0][k], x1 = u[b][1][k], py = y + k;
        if (x0 > x1) continue;
        const __m256 y_v = _mm256_set1_ps(float(py));
        uint32_t* depth_row = depth + size_t(py) * size_t(width);
        uint32_t* owner_row = owner + size_t(py) * size_t(width);
        for (int32_t px = x0; px <= x1; px += 8) {
          const __m256i column = _mm256_add_epi32(_mm256_set1_epi32(px), lanes);
          const __m256i covered = _mm256_cmpgt_epi32(_mm256_set1_epi32(x1 - px + 1), lanes);  // columns px .. x1
          const __m256 z =
              finish_depth8(mul_add8(gathered.dzdy, y_v,
                                     mul_add8(gathered.dzdx, _mm256_cvtepi32_ps(column), gathered.a0, d.fma), d.fma),
                            gathered.offset, d);
          const __m256i raw = to_raw<F>(z);
          __m256i pass = covered;
          if (px + 7 <= last_owned) {
            // all eight columns this worker's (in the visit, or in the row up to owned_row_end): read
            // and written whole, a column not covered or failing with the value it held (as
            // draw_pairs); the masked load and stores below cost lines_20k 5% more on a Zen 5 host
            // (performance-log.md). Written back even when no column passes: a branch on the test
            // is a guess wherever lines cross at random depths (lines of 10 and 20 degrees 6-8%
            // slower with it).
            __m256i* depth_at = reinterpret_cast<__m256i*>(depth_row + px);
            __m256i* owner_at = reinterpret_cast<__m256i*>(owner_row + px);
            const __m256i stored = _mm256_loadu_si256(depth_at);
            if constexpr (Op != CompareOp::Always)
              pass = _mm256_and_si256(covered, depth_passes<F, Op>(z, raw, stored));
            if (d.write) _mm256_storeu_si256(depth_at, _mm256_blendv_epi8(stored, raw, pass));
            _mm256_storeu_si256(owner_at, _mm256_blendv_epi8(_mm256_loadu_si256(owner_at), id, pass));
            continue;
          }
          if constexpr (Op != CompareOp::Always) {
            const __m256i stored = _mm256_maskload_epi32(reinterpret_cast<const int*>(depth_row + px), covered);
            pass = _mm256_and_si256(covered, depth_passes<F, Op>(z, raw, stored));
          }
          if (_mm256_testz_si256(pass, pass)) continue;
          if (d.write) _mm256_maskstore_epi32(reinterpret_cast<int*>(depth_row + px), pass, raw);
          _mm256_maskstore_epi32(reinterpret_cast<int*>(owner_row + px), pass, id);
        }
      }
    }
  }
  return true;
}

template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool depth_kernel(const RasterPrimitive& p, int32_t y0, int32_t y1, const KernelDepth& d,
                                 RenderTargets& targets, bool avx512_writes, int32_t owned_row_end) {
  if (targets.samples == 1) return thin_rows<F, Op>(p, y0, y1, d, targets, avx512_writes, owned_row_end);
  return depth_rows<F, Op>(p, y0, y1, d, targets);
}

// Without an active depth test every covered sample is written (the owner only).
RASTERCMP_AVX2 bool coverage_rows(const RasterPrimitive& p, int32_t y0, int32_t y1, RenderTargets& targets) {
  uint32_t* owner = targets.owner.data();
  const uint32_t samples = targets.samples;
  return for_each_run(p, y0, y1, p.per_sample ? samples : 1, [&](int32_t py, uint32_t s, int32_t x0, int32_t x1) {
    for (int32_t px = x0; px <= x1; ++px) {
      if (p.per_sample) {
        owner[targets.index(px, py, s)] = p.owner;
      } else {
        for (uint32_t t = 0; t < samples; ++t) owner[targets.index(px, py, t)] = p.owner;
      }
    }
  });
}

using DepthRowsFn = bool (*)(const RasterPrimitive&, int32_t, int32_t, const KernelDepth&, RenderTargets&, bool,
                             int32_t);

struct DepthRowsMaker {
  template <DepthFormat F, CompareOp Op>
  static constexpr DepthRowsFn get() {
    if constexpr (F == DepthFormat::None)
      return nullptr;
    else
      return &depth_kernel<F, Op>;
  }
};
constexpr auto kDepthRows = kernel_table<DepthRowsMaker>();

}  // namespace

bool rasterize_rows_avx2(const RasterPrimitive& p, int32_t y0, int32_t y1, const DepthTestState& depth,
                         RenderTargets& targets, bool avx512_writes, int32_t owned_row_end) {
  if (p.binned || depth.compute_when_inactive || (p.per_sample && targets.samples > kStandardSamples4x.size()))
    return false;
  if (uint64_t(targets.width) * targets.height * targets.samples > uint64_t(INT32_MAX)) return false;  // gather indices
  if (y0 > y1 || p.visit.x0 > p.visit.x1) return true;
  if (!depth.active) return coverage_rows(p, y0, y1, targets);
  if (depth.format == DepthFormat::None || targets.depth_raw.empty()) return false;
  if (depth.op == CompareOp::Never) return true;  // no covered sample passes: nothing is written
  const KernelDepth d{depth.format,     depth.op,         depth.write, depth.range.clamp,
                      depth.range.zmin, depth.range.zmax, depth.fma};
  if (p.per_sample && targets.samples == 4)
    return select_sample_rows_avx2(depth.format, depth.op)(p, y0, y1, d, targets);
  return select_kernel(kDepthRows, depth.format, depth.op)(p, y0, y1, d, targets, avx512_writes, owned_row_end);
}

}  // namespace rastercmp::cpu::fast
