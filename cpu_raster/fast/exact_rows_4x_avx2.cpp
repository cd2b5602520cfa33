// The exact rows (exact_rows_avx2.hpp) of a per-sample primitive in a 4x frame with an active
// depth test: a small one's samples tested directly in int32 (sample_box_rows), a larger one's
// covered columns per sample row, then two pixels' four samples a step, contiguous in the
// attachments (sample_span_rows). Coverage, exactness and depth: exact_rows_avx2.hpp.
#include <immintrin.h>

#include <algorithm>
#include <cstdint>

#include "cpu_raster/fast/avx2_depth.hpp"
#include "cpu_raster/fast/exact_rows_avx2.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"

namespace rastercmp::cpu::fast {
namespace {

// What a step of a per-sample primitive in a 4x frame reads and writes the same way whatever chose
// its lanes: lane l is sample l % 4 of pixel px + l / 4 (`pixel`), the step's eight values
// contiguous at dp / op (32 bytes). Its depth (sample_point's floats: float(px) + the sample's x
// offset, `y` the row's float plus the sample's y offset), the test against the stored values and
// the writes of the passing covered lanes. A step with a lane outside the row (`row_end`: those
// lanes hold another row's values) is loaded and stored masked to `covered`, which holds only
// lanes of the row; otherwise the other lanes are written back as loaded (this worker's row).
struct SampleStep {
  __m256 sx, a0, dzdx, dzdy, offset;
  __m256i id;
};

RASTERCMP_AVX2 inline SampleStep sample_step_of(const RasterPrimitive& p) {
  return SampleStep{_mm256_setr_ps(kStandardSamples4x[0].x, kStandardSamples4x[1].x, kStandardSamples4x[2].x,
                                   kStandardSamples4x[3].x, kStandardSamples4x[0].x, kStandardSamples4x[1].x,
                                   kStandardSamples4x[2].x, kStandardSamples4x[3].x),
                    _mm256_set1_ps(p.depth.a0),
                    _mm256_set1_ps(p.depth.dzdx),
                    _mm256_set1_ps(p.depth.dzdy),
                    _mm256_set1_ps(p.offset.offset),
                    _mm256_set1_epi32(int32_t(p.owner))};
}

// sample_point's y floats of a row's eight lanes: float(py) plus each lane's sample y offset.
RASTERCMP_AVX2 inline __m256 sample_step_y(int32_t py) {
  const __m256 sy = _mm256_setr_ps(kStandardSamples4x[0].y, kStandardSamples4x[1].y, kStandardSamples4x[2].y,
                                   kStandardSamples4x[3].y, kStandardSamples4x[0].y, kStandardSamples4x[1].y,
                                   kStandardSamples4x[2].y, kStandardSamples4x[3].y);
  return _mm256_add_ps(_mm256_set1_ps(float(py)), sy);
}

template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 inline void draw_sample_step(const SampleStep& c, const KernelDepth& d, __m256i pixel, __m256 y,
                                            __m256i covered, bool row_end, uint32_t* dp, uint32_t* op) {
  const __m256 x = _mm256_add_ps(_mm256_cvtepi32_ps(pixel), c.sx);
  const __m256 z = finish_depth8(mul_add8(c.dzdy, y, mul_add8(c.dzdx, x, c.a0, d.fma), d.fma), c.offset, d);
  const __m256i raw = to_raw<F>(z);
  const __m256i stored = row_end ? _mm256_maskload_epi32(reinterpret_cast<const int*>(dp), covered)
                                 : _mm256_loadu_si256(reinterpret_cast<const __m256i*>(dp));
  __m256i pass = covered;
  if constexpr (Op != CompareOp::Always) pass = _mm256_and_si256(covered, depth_passes<F, Op>(z, raw, stored));
  if (_mm256_testz_si256(pass, pass)) return;
  if (row_end) {
    if (d.write) _mm256_maskstore_epi32(reinterpret_cast<int*>(dp), pass, raw);
    _mm256_maskstore_epi32(reinterpret_cast<int*>(op), pass, c.id);
    return;
  }
  if (d.write) _mm256_storeu_si256(reinterpret_cast<__m256i*>(dp), _mm256_blendv_epi8(stored, raw, pass));
  const __m256i old = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(op));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(op), _mm256_blendv_epi8(old, c.id, pass));
}

// With an active depth test, a per-sample primitive in a 4x frame: one pixel row of the four
// samples is a contiguous run of the attachments, eight values (two pixels) per step, lane l holding
// column px + l / 4 and sample l % 4; a lane is covered when its column lies in its sample's covered
// columns. Each step loads the stored values (masked at the row's ends), tests, and writes the
// passing lanes back blended with the values it loaded (masked at the row's ends): the other lanes
// of the step are this worker's row, rewritten unchanged. (In a frame of one sample per pixel the
// same steps, eight columns wide, were slower on lines_20k than the gathered batches of depth_rows:
// a line's row touches one or two columns, and a step's 32 bytes its cache lines again.)
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool sample_span_rows(const RasterPrimitive& p, int32_t y0, int32_t y1, const KernelDepth& d,
                                     RenderTargets& targets) {
  constexpr int Samples = 4;
  constexpr int32_t kPixels = 8 / Samples;
  PlaneRows planes;
  if (!init_plane_rows(planes, p, Samples, y0, y1)) return false;
  for (uint32_t s = 0; s < uint32_t(Samples); ++s) start_sample(planes, s);
  const int32_t width = int32_t(targets.width);
  uint32_t* depth = targets.depth_raw.data();
  uint32_t* owner = targets.owner.data();
  const __m256i lane_pixel = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1);
  const __m256i lane_sample = _mm256_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3);
  const SampleStep step = sample_step_of(p);
  const __m256i one = _mm256_set1_epi32(1);
  const __m256d first = _mm256_set1_pd(double(p.visit.x0)), last = _mm256_set1_pd(double(p.visit.x1));
  // The columns of up to kChunkRows rows at a time, every row's lines asked for before the first
  // is drawn.
  constexpr int32_t kChunkRows = 64;
  alignas(16) int32_t u[kChunkRows / 4][2][Samples][4];  // [step][lo, hi][sample][row of the step]
  for (int32_t chunk = y0; chunk <= y1; chunk += kChunkRows) {
    const int32_t chunk_end = std::min(y1, chunk + kChunkRows - 1);
    for (int32_t y = chunk, b = 0; y <= chunk_end; y += 4, ++b) {
      for (uint32_t s = 0; s < uint32_t(Samples); ++s) next_plane_rows(planes, s, first, last, u[b][0][s], u[b][1][s]);
      for (int32_t k = 0; k < 4 && y + k <= chunk_end; ++k) {
        if (u[b][0][0][k] > u[b][1][0][k]) continue;
        const size_t at = (size_t(y + k) * size_t(width) + size_t(u[b][0][0][k])) * Samples;
        _mm_prefetch(reinterpret_cast<const char*>(depth + at), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(owner + at), _MM_HINT_T0);
      }
    }
    for (int32_t y = chunk, cur = 0; y <= chunk_end; y += 4, ++cur) {
      const int32_t rows = std::min(4, chunk_end - y + 1);
      for (int32_t k = 0; k < rows; ++k) {
        int32_t lo = INT32_MAX, hi = INT32_MIN;
        alignas(16) int32_t x0[4] = {0, 0, 0, 0}, x1[4] = {-1, -1, -1, -1};
        for (int s = 0; s < Samples; ++s) {
          x0[s] = u[cur][0][s][k];
          x1[s] = u[cur][1][s][k];
          if (x0[s] > x1[s]) continue;
          lo = std::min(lo, x0[s]);
          hi = std::max(hi, x1[s]);
        }
        if (lo > hi) continue;
        // per lane: its sample's first column - 1 and last column + 1
        const __m256i x0_v = _mm256_permutevar8x32_epi32(
            _mm256_castsi128_si256(_mm_load_si128(reinterpret_cast<const __m128i*>(x0))), lane_sample);
        const __m256i x1_v = _mm256_permutevar8x32_epi32(
            _mm256_castsi128_si256(_mm_load_si128(reinterpret_cast<const __m128i*>(x1))), lane_sample);
        const __m256i before = _mm256_sub_epi32(x0_v, one), after = _mm256_add_epi32(x1_v, one);
        const int32_t py = y + k;
        const __m256 y_v = sample_step_y(py);
        uint32_t* depth_row = depth + size_t(py) * size_t(width) * Samples;
        uint32_t* owner_row = owner + size_t(py) * size_t(width) * Samples;
        // steps on 32-byte boundaries of the attachments (both start on one), so a step's values lie
        // in one cache line: the first may start up to kPixels - 1 columns before the row
        const int32_t start = lo - int32_t((size_t(py) * size_t(width) + size_t(lo)) & size_t(kPixels - 1));
        for (int32_t px = start; px <= hi; px += kPixels) {
          const __m256i pixel = _mm256_add_epi32(_mm256_set1_epi32(px), lane_pixel);
          const __m256i covered = _mm256_and_si256(_mm256_cmpgt_epi32(pixel, before), _mm256_cmpgt_epi32(after, pixel));
          const bool row_end = px < 0 || px + kPixels > width;  // lanes outside the row: other rows' values
          draw_sample_step<F, Op>(step, d, pixel, y_v, covered, row_end, depth_row + ptrdiff_t(px) * Samples,
                                  owner_row + ptrdiff_t(px) * Samples);
        }
      }
    }
  }
  return true;
}

// A small per-sample primitive in a 4x frame: every sample of its visit rectangle's pixels tested
// directly, in the steps and lanes of sample_span_rows (two pixels' four samples, on 32-byte
// boundaries), plane values in int32. n = E - 1 of plane i at lane (column px, sample s) of row py
// is c + (dcdy * sy[s] - dcdx * sx[s]) + (px - start) * gx + (py - y0) * gy, with c its value at
// the corner of pixel (start, y0), gx = -dcdx * 256, gy = dcdy * 256 and the sample offsets sx, sy
// in (0, 256): an integer, covered iff n >= 0 for every plane, so iff the OR of the planes' n has
// its sign bit clear. Exact when every value the steps form fits int32: over the columns
// [start, x1 + 1] and rows [y0, y1] (start = x0 - 1), |n| < |c| + |gx| * (x1 + 2 - start) +
// |gy| * (y1 - y0 + 1), checked below 2^31 in int64 per plane (the row step past y1 may wrap; it
// is never read). Lanes outside [x0, x1] are masked: the exact path visits only those columns. A
// step with no covered lane computes no depth. False, having written nothing, when a bound fails.

// Planes: p.planes.count, or 0 for any count up to 8 (a triangle without scissor planes has 3,
// kept in registers).
template <DepthFormat F, CompareOp Op, uint32_t Planes>
RASTERCMP_AVX2 bool sample_box_rows(const RasterPrimitive& p, int32_t y0, int32_t y1, const KernelDepth& d,
                                    RenderTargets& targets) {
  constexpr int Samples = 4;
  const int32_t x0 = p.visit.x0, x1 = p.visit.x1, width = int32_t(targets.width);
  const uint32_t planes = Planes != 0 ? Planes : p.planes.count;
  // a row's first step starts on an even pixel of the attachments (a 32-byte boundary): at x0 - 1
  // or x0, after the parity of the row's first pixel
  const int32_t start = x0 - 1;
  const int64_t reach_x = int64_t(x1) + 2 - start, reach_y = int64_t(y1) - y0 + 1;
  const __m256i lane_pixel = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1);
  const __m256i lane_x =
      _mm256_setr_epi32(kStandardSamples4x[0].x_fixed, kStandardSamples4x[1].x_fixed, kStandardSamples4x[2].x_fixed,
                        kStandardSamples4x[3].x_fixed, kStandardSamples4x[0].x_fixed, kStandardSamples4x[1].x_fixed,
                        kStandardSamples4x[2].x_fixed, kStandardSamples4x[3].x_fixed);
  const __m256i lane_y =
      _mm256_setr_epi32(kStandardSamples4x[0].y_fixed, kStandardSamples4x[1].y_fixed, kStandardSamples4x[2].y_fixed,
                        kStandardSamples4x[3].y_fixed, kStandardSamples4x[0].y_fixed, kStandardSamples4x[1].y_fixed,
                        kStandardSamples4x[2].y_fixed, kStandardSamples4x[3].y_fixed);
  __m256i row_n[8], gx1[8], gx2[8], gy[8];
  for (uint32_t i = 0; i < planes; ++i) {
    // lane (pixel k, sample s) of the first step: n at the pixel's corner, plus the sample's offset
    // (below 256 fixed units each way) and k pixels; every term and sum within the bound
    const EdgePlane& plane = p.planes.plane[i];
    BoxPlane b;
    if (!box_plane(plane, start, y0, reach_x, reach_y, b)) return false;
    const __m256i offsets = _mm256_sub_epi32(_mm256_mullo_epi32(_mm256_set1_epi32(int32_t(plane.dcdy)), lane_y),
                                             _mm256_mullo_epi32(_mm256_set1_epi32(int32_t(plane.dcdx)), lane_x));
    gx1[i] = _mm256_set1_epi32(int32_t(b.gx));
    row_n[i] = _mm256_add_epi32(_mm256_add_epi32(_mm256_set1_epi32(int32_t(b.corner)), offsets),
                                _mm256_mullo_epi32(gx1[i], lane_pixel));
    gx2[i] = _mm256_set1_epi32(int32_t(2 * b.gx));
    gy[i] = _mm256_set1_epi32(int32_t(b.gy));
  }
  uint32_t* depth = targets.depth_raw.data();
  uint32_t* owner = targets.owner.data();
  const SampleStep step = sample_step_of(p);
  const __m256i before = _mm256_set1_epi32(x0 - 1), after = _mm256_set1_epi32(x1 + 1);
  for (int32_t py = y0; py <= y1; ++py) {
    const int32_t first = x0 - int32_t((size_t(py) * size_t(width) + size_t(x0)) & 1u);  // start or start + 1
    __m256i n[8];
    for (uint32_t i = 0; i < planes; ++i) {
      n[i] = first == start ? row_n[i] : _mm256_add_epi32(row_n[i], gx1[i]);
      row_n[i] = _mm256_add_epi32(row_n[i], gy[i]);
    }
    const __m256 y_v = sample_step_y(py);
    uint32_t* depth_row = depth + size_t(py) * size_t(width) * Samples;
    uint32_t* owner_row = owner + size_t(py) * size_t(width) * Samples;
    for (int32_t px = first; px <= x1; px += 2) {
      __m256i any_out = n[0];
      n[0] = _mm256_add_epi32(n[0], gx2[0]);
      for (uint32_t i = 1; i < planes; ++i) {
        any_out = _mm256_or_si256(any_out, n[i]);
        n[i] = _mm256_add_epi32(n[i], gx2[i]);
      }
      if (_mm256_movemask_ps(_mm256_castsi256_ps(any_out)) == 0xFF) continue;  // every lane outside a plane
      const __m256i pixel = _mm256_add_epi32(_mm256_set1_epi32(px), lane_pixel);
      const __m256i inside = _mm256_and_si256(_mm256_cmpgt_epi32(pixel, before), _mm256_cmpgt_epi32(after, pixel));
      const __m256i covered = _mm256_andnot_si256(_mm256_srai_epi32(any_out, 31), inside);
      if (_mm256_testz_si256(covered, covered)) continue;
      const bool row_end = px < 0 || px + 2 > width;  // lanes outside the row: other rows' values
      draw_sample_step<F, Op>(step, d, pixel, y_v, covered, row_end, depth_row + ptrdiff_t(px) * Samples,
                              owner_row + ptrdiff_t(px) * Samples);
    }
  }
  return true;
}

// The box kernel for a small primitive (at most kBoxColumns columns and kBoxPixels pixels), the
// span rows for any other or where the box's int32 bounds fail.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool sample_rows(const RasterPrimitive& p, int32_t y0, int32_t y1, const KernelDepth& d,
                                RenderTargets& targets) {
  const int32_t columns = p.visit.x1 - p.visit.x0 + 1;
  if (columns <= kBoxColumns && columns * (y1 - y0 + 1) <= kBoxPixels &&
      (p.planes.count == 3 ? sample_box_rows<F, Op, 3>(p, y0, y1, d, targets)
                           : sample_box_rows<F, Op, 0>(p, y0, y1, d, targets)))
    return true;
  return sample_span_rows<F, Op>(p, y0, y1, d, targets);
}

struct SampleRowsMaker {
  template <DepthFormat F, CompareOp Op>
  static constexpr SampleRowsFn get() {
    if constexpr (F == DepthFormat::None)
      return nullptr;
    else
      return &sample_rows<F, Op>;
  }
};
constexpr auto kSampleRows = kernel_table<SampleRowsMaker>();

}  // namespace

SampleRowsFn select_sample_rows_avx2(DepthFormat format, CompareOp op) {
  return select_kernel(kSampleRows, format, op);
}

}  // namespace rastercmp::cpu::fast
