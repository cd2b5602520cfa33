// Depth arithmetic of sixteen lanes, shared by the AVX-512 translation units (include only from
// code compiled for AVX-512: every function carries RASTERCMP_AVX512): avx2_depth.hpp's
// operations, one IEEE operation per intrinsic, on sixteen lanes.
#pragma once

// GCC 12's own AVX-512 headers pass _mm512_undefined_*() as the merge source of unmasked
// operations, which -Wuninitialized reports at every use once inlined (a false positive). The
// translation units with 512-bit intrinsics include this header before their code.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <immintrin.h>

#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"
#include "model/depth_format.hpp"

namespace rastercmp::cpu::fast {

// FMA?(a, b, c) (mul_add8).
RASTERCMP_AVX512 inline __m512 mul_add16(__m512 a, __m512 b, __m512 c, bool fma) {
  return fma ? _mm512_fmadd_ps(a, b, c) : _mm512_add_ps(_mm512_mul_ps(a, b), c);
}

// The draw's depth state in registers (KernelDepth's fields, read once per block: stores to
// the attachments go to memory the compiler cannot tell apart from a KernelDepth).
struct Depth16 {
  bool fma, clamp, write;
  __m512 zmin, zmax;
};

RASTERCMP_AVX512 inline Depth16 depth16(const KernelDepth& d) {
  return Depth16{d.fma, d.clamp, d.write, _mm512_set1_ps(d.zmin), _mm512_set1_ps(d.zmax)};
}

// finish_depth8 after its + o: min(z, 1), max(z, 0), the depth clamp; vminps/vmaxps return their
// second operand on NaN and when both operands are zeros. The tile kernel adds o first; small
// triangles (draws without depth bias, o = 0) leave the z + 0 out: it changes only -0 (into +0),
// and max(min(-0, 1), +0) is already the second operand, +0; NaN stays NaN through it and becomes
// 1 through min(z, 1) either way.
RASTERCMP_AVX512 inline __m512 finish_depth16(__m512 z, const Depth16& d) {
  z = _mm512_max_ps(_mm512_min_ps(z, _mm512_set1_ps(1.0f)), _mm512_setzero_ps());
  if (d.clamp) z = _mm512_max_ps(_mm512_min_ps(z, d.zmax), d.zmin);
  return z;
}

// to_raw (§3.5): D24 by cvtps2dq (nearest even), D16 by the magic add.
// The conversion is the one the depth-format table names for F (to_raw in avx2_depth.hpp).
template <DepthFormat F>
RASTERCMP_AVX512 inline __m512i to_raw16(__m512 z) {
  constexpr DepthFormatInfo kInfo = depth_format_info(F);
  if constexpr (kInfo.conversion == DepthConversion::FloatBits) {
    return _mm512_castps_si512(z);
  } else if constexpr (kInfo.conversion == DepthConversion::ScaleRound) {
    return _mm512_cvtps_epi32(_mm512_mul_ps(z, _mm512_set1_ps(float(unorm_max(kInfo)))));
  } else {
    static_assert(kInfo.conversion == DepthConversion::MagicNumber, "no depth, nothing to convert");
    const __m512 magic =
        _mm512_add_ps(_mm512_mul_ps(z, _mm512_set1_ps(magic_scale(kInfo))), _mm512_set1_ps(magic_bias(kInfo)));
    return _mm512_and_si512(_mm512_castps_si512(magic), _mm512_set1_epi32(int(kInfo.raw_mask)));
  }
}

// depth_test_passes (§3.6) on the covered lanes: D32 with the unordered predicates (true whenever
// NaN is involved), UNORM unsigned.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 inline __mmask16 passing(__mmask16 covered, __m512i fragment, __m512i stored) {
  if constexpr (F == DepthFormat::None || Op == CompareOp::Always) {
    return covered;
  } else if constexpr (Op == CompareOp::Never) {
    return 0;
  } else if constexpr (is_float(F)) {
    const __m512 a = _mm512_castsi512_ps(fragment), b = _mm512_castsi512_ps(stored);
    if constexpr (Op == CompareOp::Less) return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NGE_UQ);  // !(a >= b)
    if constexpr (Op == CompareOp::Equal)
      return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_EQ_UQ);  // !(a < b) && !(a > b)
    if constexpr (Op == CompareOp::LessOrEqual) return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NGT_UQ);
    if constexpr (Op == CompareOp::Greater) return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NLE_UQ);
    if constexpr (Op == CompareOp::NotEqual) return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NEQ_UQ);
    return _mm512_mask_cmp_ps_mask(covered, a, b, _CMP_NLT_UQ);  // GreaterOrEqual: !(a < b)
  } else {
    if constexpr (Op == CompareOp::Less) return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_LT);
    if constexpr (Op == CompareOp::Equal) return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_EQ);
    if constexpr (Op == CompareOp::LessOrEqual)
      return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_LE);
    if constexpr (Op == CompareOp::Greater)
      return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_NLE);
    if constexpr (Op == CompareOp::NotEqual)
      return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_NE);
    return _mm512_mask_cmp_epu32_mask(covered, fragment, stored, _MM_CMPINT_NLT);  // GreaterOrEqual
  }
}

}  // namespace rastercmp::cpu::fast
