// Depth arithmetic of eight lanes, shared by the AVX2 translation units (include only from code
// compiled for AVX2: every function carries RASTERCMP_AVX2). Each intrinsic is one IEEE operation
// of the scalar exact path (depth_sample.cpp, docs/lavapipe-rules.md §3.3-§3.5): _mm256_min_ps and
// _mm256_max_ps return their second operand on NaN, as sse_min / sse_max do.
#pragma once

#include <immintrin.h>

#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"
#include "model/depth_format.hpp"

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

// depth_to_raw (§3.5), by the conversion the depth-format table names for F.
template <DepthFormat F>
RASTERCMP_AVX2 inline __m256i to_raw(__m256 z) {
  constexpr DepthFormatInfo kInfo = depth_format_info(F);
  if constexpr (kInfo.conversion == DepthConversion::FloatBits) {
    return _mm256_castps_si256(z);
  } else if constexpr (kInfo.conversion == DepthConversion::ScaleRound) {  // D24: z * 16777215, cvtps2dq
    return _mm256_cvtps_epi32(_mm256_mul_ps(z, _mm256_set1_ps(float(unorm_max(kInfo)))));  // nearest even
  } else {
    static_assert(kInfo.conversion == DepthConversion::MagicNumber, "no depth, nothing to convert");
    // D16: z * 65535/65536 + 128, & 0xFFFF
    const __m256 magic =
        _mm256_add_ps(_mm256_mul_ps(z, _mm256_set1_ps(magic_scale(kInfo))), _mm256_set1_ps(magic_bias(kInfo)));
    return _mm256_and_si256(_mm256_castps_si256(magic), _mm256_set1_epi32(int(kInfo.raw_mask)));
  }
}

}  // namespace rastercmp::cpu::fast
