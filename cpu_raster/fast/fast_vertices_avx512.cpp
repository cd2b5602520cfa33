// AVX-512 twin of transform_vertices_scalar (and of the AVX2 pass): 16 positions at a time, the
// same IEEE operations in the same order (1/w, x*(1/w), then fused or separate *scale + translate;
// §1.3), the same unordered clip compares and the same round-to-nearest-even snap (§2.2); the
// lane masks replace the AVX2 pass's blends.
#include "cpu_raster/fast/avx512_depth.hpp"  // first: GCC 12's AVX-512 headers' false warnings off
//
#include <immintrin.h>

#include "cpu_raster/exact/fixed_point.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/fast_vertices.hpp"

namespace rastercmp::cpu::fast {
namespace {

struct Columns16 {
  __m512 x, y, z, w;
};

// Sixteen glm::vec4 (x, y, z, w contiguous) → one register per component: the x and y (z and w)
// of eight vertices from each pair of loads, then the two halves joined.
RASTERCMP_AVX512 inline Columns16 load_columns16(const float* p) {
  const __m512 v0 = _mm512_loadu_ps(p), v1 = _mm512_loadu_ps(p + 16);
  const __m512 v2 = _mm512_loadu_ps(p + 32), v3 = _mm512_loadu_ps(p + 48);
  const __m512i first_two = _mm512_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28, 1, 5, 9, 13, 17, 21, 25, 29);
  const __m512i last_two = _mm512_add_epi32(first_two, _mm512_set1_epi32(2));
  const __m512 xy_lo = _mm512_permutex2var_ps(v0, first_two, v1), xy_hi = _mm512_permutex2var_ps(v2, first_two, v3);
  const __m512 zw_lo = _mm512_permutex2var_ps(v0, last_two, v1), zw_hi = _mm512_permutex2var_ps(v2, last_two, v3);
  const __m512i low = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23);
  const __m512i high = _mm512_add_epi32(low, _mm512_set1_epi32(8));
  return Columns16{_mm512_permutex2var_ps(xy_lo, low, xy_hi), _mm512_permutex2var_ps(xy_lo, high, xy_hi),
                   _mm512_permutex2var_ps(zw_lo, low, zw_hi), _mm512_permutex2var_ps(zw_lo, high, zw_hi)};
}

// cpu::window_from_clip_jit for one component.
RASTERCMP_AVX512 inline __m512 to_window16(__m512 c, __m512 oow, float scale, float translate, bool fma) {
  const __m512 ndc = _mm512_mul_ps(c, oow);
  if (fma) return _mm512_fmadd_ps(ndc, _mm512_set1_ps(scale), _mm512_set1_ps(translate));
  return _mm512_add_ps(_mm512_mul_ps(ndc, _mm512_set1_ps(scale)), _mm512_set1_ps(translate));
}

// unordered_greater(a, b) = !(a <= b): bit `bit` of the clip mask in the lanes where it holds.
RASTERCMP_AVX512 inline __m512i clip_bit16(__m512 a, __m512 b, int bit) {
  return _mm512_maskz_mov_epi32(_mm512_cmp_ps_mask(a, b, _CMP_NLE_UQ), _mm512_set1_epi32(1 << bit));
}

RASTERCMP_AVX512 inline __m512i clip_mask16(const Columns16& p, bool depth_clip) {
  const __m512 zero = _mm512_setzero_ps();
  __m512i mask = _mm512_or_si512(clip_bit16(p.x, p.w, 0), clip_bit16(zero, _mm512_add_ps(p.x, p.w), 1));
  mask = _mm512_or_si512(mask, _mm512_or_si512(clip_bit16(p.y, p.w, 2), clip_bit16(zero, _mm512_add_ps(p.y, p.w), 3)));
  if (depth_clip) mask = _mm512_or_si512(mask, _mm512_or_si512(clip_bit16(zero, p.z, 4), clip_bit16(p.z, p.w, 5)));
  return mask;
}

// snap_vertex: rne(fl(x - 0.5) * 256); `ok` clear for NaN or |value| > kMaxMagnitude (and the
// value 0 there).
RASTERCMP_AVX512 inline __m512i snap16(__m512 window, __mmask16& ok) {
  const __m512 scaled = _mm512_mul_ps(_mm512_sub_ps(window, _mm512_set1_ps(0.5f)), _mm512_set1_ps(float(kFixedOne)));
  const __m512 rounded = _mm512_roundscale_ps(scaled, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  const __m512 magnitude = _mm512_abs_ps(rounded);
  ok = _mm512_cmp_ps_mask(magnitude, _mm512_set1_ps(float(Fixed24_8::kMaxMagnitude)), _CMP_LE_OQ);
  return _mm512_maskz_cvtps_epi32(ok, rounded);
}

// Columns (x, y, z, flags) of sixteen vertices → sixteen 16-byte rows: load_columns16 backwards.
RASTERCMP_AVX512 inline void store_vertices16(__m512 x, __m512 y, __m512 z, __m512i flags, FastVertex* out) {
  const __m512 f = _mm512_castsi512_ps(flags);
  const __m512i pairs_lo = _mm512_setr_epi32(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
  const __m512i pairs_hi = _mm512_add_epi32(pairs_lo, _mm512_set1_epi32(8));
  const __m512 xy_lo = _mm512_permutex2var_ps(x, pairs_lo, y), xy_hi = _mm512_permutex2var_ps(x, pairs_hi, y);
  const __m512 zf_lo = _mm512_permutex2var_ps(z, pairs_lo, f), zf_hi = _mm512_permutex2var_ps(z, pairs_hi, f);
  const __m512i quads_lo = _mm512_setr_epi32(0, 1, 16, 17, 2, 3, 18, 19, 4, 5, 20, 21, 6, 7, 22, 23);
  const __m512i quads_hi = _mm512_add_epi32(quads_lo, _mm512_set1_epi32(8));
  float* o = reinterpret_cast<float*>(out);
  _mm512_storeu_ps(o + 0, _mm512_permutex2var_ps(xy_lo, quads_lo, zf_lo));
  _mm512_storeu_ps(o + 16, _mm512_permutex2var_ps(xy_lo, quads_hi, zf_lo));
  _mm512_storeu_ps(o + 32, _mm512_permutex2var_ps(xy_hi, quads_lo, zf_hi));
  _mm512_storeu_ps(o + 48, _mm512_permutex2var_ps(xy_hi, quads_hi, zf_hi));
}

}  // namespace

RASTERCMP_AVX512 uint32_t transform_vertices_avx512(const VertexJob& job, size_t begin, size_t end, FastVertex* out,
                                                    int16_t* rows) {
  const ViewportTransform& vp = job.viewport;
  size_t k = begin;
  __m512i all_flags = _mm512_setzero_si512();
  for (; k + 16 <= end; k += 16) {
    const Columns16 p = load_columns16(&job.pos_clip[k].x);
    const __m512 oow = _mm512_div_ps(_mm512_set1_ps(1.0f), p.w);
    const __m512 x = to_window16(p.x, oow, vp.scale[0], vp.translate[0], job.fma);
    const __m512 y = to_window16(p.y, oow, vp.scale[1], vp.translate[1], job.fma);
    const __m512 z = to_window16(p.z, oow, vp.scale[2], vp.translate[2], job.fma);
    __mmask16 ok_x, ok_y;
    snap16(x, ok_x);  // only whether it succeeds: the set-up snaps again (snap_fixed)
    const __m512i fy = snap16(y, ok_y);
    const __m512i clip = clip_mask16(p, job.depth_clip);
    const __m512i flags =
        _mm512_mask_or_epi32(clip, __mmask16(~(ok_x & ok_y)), clip, _mm512_set1_epi32(int(kVertexSnapFailed)));
    all_flags = _mm512_or_si512(all_flags, flags);
    // the tile row of y (unknown_row(flags) where a flag is set), packed to 16 bits
    const __mmask16 known = _mm512_cmpeq_epi32_mask(flags, _mm512_setzero_si512());
    const __m512i row = _mm512_mask_blend_epi32(known, _mm512_or_si512(_mm512_set1_epi32(kRowUnknown), flags),
                                                _mm512_srai_epi32(fy, kFixedOrder + 6));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(rows + k), _mm512_cvtsepi32_epi16(row));
    store_vertices16(x, y, z, flags, out + k);  // sixteen FastVertex {x, y, z, flags}
  }
  return transform_vertices_scalar(job, k, end, out, rows) | uint32_t(_mm512_reduce_or_epi32(all_flags));
}

}  // namespace rastercmp::cpu::fast
