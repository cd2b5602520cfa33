// AVX2 twin of transform_vertices_scalar: 8 positions at a time, the same IEEE operations in the
// same order (1/w, x*(1/w), then fused or separate *scale + translate; §1.3), the same unordered
// clip compares and the same round-to-nearest-even snap (§2.2).
#include <immintrin.h>

#include "cpu_raster/exact/fixed_point.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/fast_vertices.hpp"

namespace rastercmp::cpu::fast {
namespace {

struct Columns {
  __m256 x, y, z, w;
};

RASTERCMP_AVX2 inline __m256 load_pair(const float* p, int a, int b) {
  return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4 * a)), _mm_loadu_ps(p + 4 * b), 1);
}

// Eight glm::vec4 (x, y, z, w contiguous) → one register per component.
RASTERCMP_AVX2 inline Columns load_columns(const float* p) {
  const __m256 a0 = load_pair(p, 0, 4), a1 = load_pair(p, 1, 5), a2 = load_pair(p, 2, 6), a3 = load_pair(p, 3, 7);
  const __m256 t0 = _mm256_unpacklo_ps(a0, a1), t1 = _mm256_unpackhi_ps(a0, a1);
  const __m256 t2 = _mm256_unpacklo_ps(a2, a3), t3 = _mm256_unpackhi_ps(a2, a3);
  return Columns{_mm256_shuffle_ps(t0, t2, 0x44), _mm256_shuffle_ps(t0, t2, 0xEE), _mm256_shuffle_ps(t1, t3, 0x44),
                 _mm256_shuffle_ps(t1, t3, 0xEE)};
}

// cpu::window_from_clip_jit for one component.
RASTERCMP_AVX2 inline __m256 to_window(__m256 c, __m256 oow, float scale, float translate, bool fma) {
  const __m256 ndc = _mm256_mul_ps(c, oow);
  if (fma) return _mm256_fmadd_ps(ndc, _mm256_set1_ps(scale), _mm256_set1_ps(translate));
  return _mm256_add_ps(_mm256_mul_ps(ndc, _mm256_set1_ps(scale)), _mm256_set1_ps(translate));
}

// unordered_greater(a, b) = !(a <= b), one bit of the clip mask.
RASTERCMP_AVX2 inline __m256i clip_bit(__m256 a, __m256 b, int bit) {
  return _mm256_and_si256(_mm256_castps_si256(_mm256_cmp_ps(a, b, _CMP_NLE_UQ)), _mm256_set1_epi32(1 << bit));
}

RASTERCMP_AVX2 inline __m256i clip_mask8(const Columns& p, bool depth_clip) {
  const __m256 zero = _mm256_setzero_ps();
  __m256i mask = _mm256_or_si256(clip_bit(p.x, p.w, 0), clip_bit(zero, _mm256_add_ps(p.x, p.w), 1));
  mask = _mm256_or_si256(mask, _mm256_or_si256(clip_bit(p.y, p.w, 2), clip_bit(zero, _mm256_add_ps(p.y, p.w), 3)));
  if (depth_clip) mask = _mm256_or_si256(mask, _mm256_or_si256(clip_bit(zero, p.z, 4), clip_bit(p.z, p.w, 5)));
  return mask;
}

// snap_vertex: rne(fl(x - 0.5) * 256); `ok` is false for NaN or |value| > kMaxMagnitude.
RASTERCMP_AVX2 inline __m256i snap8(__m256 window, __m256& ok) {
  const __m256 scaled = _mm256_mul_ps(_mm256_sub_ps(window, _mm256_set1_ps(0.5f)), _mm256_set1_ps(float(kFixedOne)));
  const __m256 rounded = _mm256_round_ps(scaled, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  const __m256 magnitude = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), rounded);
  ok = _mm256_cmp_ps(magnitude, _mm256_set1_ps(float(Fixed24_8::kMaxMagnitude)), _CMP_LE_OQ);
  return _mm256_and_si256(_mm256_cvtps_epi32(_mm256_and_ps(rounded, ok)), _mm256_castps_si256(ok));
}

// Columns (x, y, z, flags) of eight vertices → eight 16-byte rows: a 4x8 transpose.
RASTERCMP_AVX2 inline void store_vertices(__m256 x, __m256 y, __m256 z, __m256i flags, FastVertex* out) {
  const __m256 f = _mm256_castsi256_ps(flags);
  const __m256 a0 = _mm256_unpacklo_ps(x, y), a1 = _mm256_unpackhi_ps(x, y);  // x0 y0 x1 y1 | x4 y4 x5 y5; 2, 3 | 6, 7
  const __m256 b0 = _mm256_unpacklo_ps(z, f), b1 = _mm256_unpackhi_ps(z, f);
  const __m256 v04 = _mm256_shuffle_ps(a0, b0, 0x44),
               v15 = _mm256_shuffle_ps(a0, b0, 0xEE);  // vertex 0 | vertex 4, ...
  const __m256 v26 = _mm256_shuffle_ps(a1, b1, 0x44), v37 = _mm256_shuffle_ps(a1, b1, 0xEE);
  float* o = reinterpret_cast<float*>(out);
  _mm256_storeu_ps(o + 0, _mm256_permute2f128_ps(v04, v15, 0x20));
  _mm256_storeu_ps(o + 8, _mm256_permute2f128_ps(v26, v37, 0x20));
  _mm256_storeu_ps(o + 16, _mm256_permute2f128_ps(v04, v15, 0x31));
  _mm256_storeu_ps(o + 24, _mm256_permute2f128_ps(v26, v37, 0x31));
}

}  // namespace

RASTERCMP_AVX2 uint32_t transform_vertices_avx2(const VertexJob& job, size_t begin, size_t end, FastVertex* out,
                                                int16_t* rows) {
  const ViewportTransform& vp = job.viewport;
  size_t k = begin;
  __m256i all_flags = _mm256_setzero_si256();
  for (; k + 8 <= end; k += 8) {
    const Columns p = load_columns(&job.pos_clip[k].x);
    const __m256 oow = _mm256_div_ps(_mm256_set1_ps(1.0f), p.w);
    const __m256 x = to_window(p.x, oow, vp.scale[0], vp.translate[0], job.fma);
    const __m256 y = to_window(p.y, oow, vp.scale[1], vp.translate[1], job.fma);
    const __m256 z = to_window(p.z, oow, vp.scale[2], vp.translate[2], job.fma);
    __m256 ok_x, ok_y;
    snap8(x, ok_x);  // only whether it succeeds: the set-up snaps again (snap_fixed)
    const __m256i fy = snap8(y, ok_y);
    const __m256i failed =
        _mm256_andnot_si256(_mm256_castps_si256(_mm256_and_ps(ok_x, ok_y)), _mm256_set1_epi32(int(kVertexSnapFailed)));
    const __m256i lane_flags = _mm256_or_si256(clip_mask8(p, job.depth_clip), failed);
    all_flags = _mm256_or_si256(all_flags, lane_flags);
    // the tile row of y (unknown_row(flags) where a flag is set), packed to 16 bits
    const __m256i row = _mm256_blendv_epi8(
        _mm256_srai_epi32(fy, kFixedOrder + 6), _mm256_or_si256(_mm256_set1_epi32(kRowUnknown), lane_flags),
        _mm256_xor_si256(_mm256_cmpeq_epi32(lane_flags, _mm256_setzero_si256()), _mm256_set1_epi32(-1)));
    const __m128i row16 = _mm_packs_epi32(_mm256_castsi256_si128(row), _mm256_extracti128_si256(row, 1));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(rows + k), row16);
    store_vertices(x, y, z, lane_flags, out + k);  // eight FastVertex {x, y, z, flags}
  }
  alignas(32) uint32_t lanes[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), all_flags);
  uint32_t result = transform_vertices_scalar(job, k, end, out, rows);
  for (uint32_t lane : lanes) result |= lane;
  return result;
}

}  // namespace rastercmp::cpu::fast
