// Float arithmetic with the rounding lavapipe uses. The project builds with -ffp-contract=off,
// so `a * b + c` below is two roundings and std::fma is one (docs/lavapipe-rules.md §1.3, §7.1).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

namespace rastercmp::cpu {

// llvm.fmuladd as the JIT emits it: fused on an FMA host, multiply-then-add otherwise.
inline float mul_add(float a, float b, float c, bool fused) { return fused ? std::fma(a, b, c) : a * b + c; }

// SSE minps/maxps: the second operand is returned when the comparison is unordered
// (gallivm lp_build_min/max with GALLIVM_NAN_BEHAVIOR_UNDEFINED).
inline float sse_min(float a, float b) { return a < b ? a : b; }
inline float sse_max(float a, float b) { return a > b ? a : b; }

// LLVM's unordered "greater than": true when a > b or either operand is NaN.
inline bool unordered_greater(float a, float b) { return !(a <= b); }

inline uint32_t float_bits(float value) { return std::bit_cast<uint32_t>(value); }
inline float float_from_bits(uint32_t bits) { return std::bit_cast<float>(bits); }

// Mesa's util_is_inf_or_nan.
inline bool is_inf_or_nan(float value) { return !std::isfinite(value); }

}  // namespace rastercmp::cpu
