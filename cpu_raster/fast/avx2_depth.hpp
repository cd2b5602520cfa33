// Depth arithmetic of eight lanes, shared by the AVX2 translation units (include only from code
// compiled for AVX2: every function carries RASTERCMP_AVX2). Each intrinsic is one IEEE operation
// of the scalar exact path (depth_sample.cpp, docs/lavapipe-rules.md §3.3-§3.5): _mm256_min_ps and
// _mm256_max_ps return their second operand on NaN, as sse_min / sse_max do.
#pragma once

#include <immintrin.h>

#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"

namespace rastercmp::cpu::fast {

// FMA?(a, b, c): one rounding when fused, a multiply and an add otherwise (never contracted).
RASTERCMP_AVX2 inline __m256 mul_add8(__m256 a, __m256 b, __m256 c, bool fma) {
  return fma ? _mm256_fmadd_ps(a, b, c) : _mm256_add_ps(_mm256_mul_ps(a, b), c);
}

// z + o, min(z, 1), max(z, 0), and the depth clamp.
RASTERCMP_AVX2 inline __m256 finish_depth8(__m256 z, __m256 offset, const KernelDepth& d) {
  z = _mm256_add_ps(z, offset);
  z = _mm256_max_ps(_mm256_min_ps(z, _mm256_set1_ps(1.0f)), _mm256_setzero_ps());
  if (d.clamp) z = _mm256_max_ps(_mm256_min_ps(z, _mm256_set1_ps(d.zmax)), _mm256_set1_ps(d.zmin));
  return z;
}

// depth_to_raw (§3.5).
template <DepthFormat F>
RASTERCMP_AVX2 inline __m256i to_raw(__m256 z) {
  if constexpr (F == DepthFormat::D32Sfloat) {
    return _mm256_castps_si256(z);
  } else if constexpr (F == DepthFormat::X8D24Unorm) {
    return _mm256_cvtps_epi32(_mm256_mul_ps(z, _mm256_set1_ps(16777215.0f)));  // cvtps2dq: nearest even
  } else {
    const __m256 magic = _mm256_add_ps(_mm256_mul_ps(z, _mm256_set1_ps(0.9999847412109375f)), _mm256_set1_ps(128.0f));
    return _mm256_and_si256(_mm256_castps_si256(magic), _mm256_set1_epi32(0xFFFF));
  }
}

}  // namespace rastercmp::cpu::fast
