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

template <CompareOp Op>
constexpr int unordered_predicate() {  // depth_test_passes for D32: true whenever NaN is involved
  switch (Op) {
    case CompareOp::Less: return _CMP_NGE_UQ;
    case CompareOp::Equal: return _CMP_EQ_UQ;
    case CompareOp::LessOrEqual: return _CMP_NGT_UQ;
    case CompareOp::Greater: return _CMP_NLE_UQ;
    case CompareOp::NotEqual: return _CMP_NEQ_UQ;
    case CompareOp::GreaterOrEqual: return _CMP_NLT_UQ;
    default: return _CMP_TRUE_UQ;
  }
}

// depth_test_passes(op, format, fragment, stored) per lane (Never and Always never get here): the
// float compares use the unordered predicates of docs/lavapipe-rules.md §3.6; UNORM depth stays
// below 2^24, so a signed 32-bit compare orders it as the unsigned one does.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 inline __m256i depth_passes(__m256 z, __m256i raw, __m256i stored) {
  if constexpr (is_float(F)) {
    return _mm256_castps_si256(_mm256_cmp_ps(z, _mm256_castsi256_ps(stored), unordered_predicate<Op>()));
  } else {
    const __m256i ones = _mm256_set1_epi32(-1);
    if constexpr (Op == CompareOp::Less) return _mm256_cmpgt_epi32(stored, raw);
    if constexpr (Op == CompareOp::Equal) return _mm256_cmpeq_epi32(raw, stored);
    if constexpr (Op == CompareOp::LessOrEqual) return _mm256_xor_si256(_mm256_cmpgt_epi32(raw, stored), ones);
    if constexpr (Op == CompareOp::Greater) return _mm256_cmpgt_epi32(raw, stored);
    if constexpr (Op == CompareOp::NotEqual) return _mm256_xor_si256(_mm256_cmpeq_epi32(raw, stored), ones);
    if constexpr (Op == CompareOp::GreaterOrEqual) return _mm256_xor_si256(_mm256_cmpgt_epi32(stored, raw), ones);
    return ones;
  }
}

}  // namespace rastercmp::cpu::fast
