// Float arithmetic with the rounding lavapipe uses. The project builds with -ffp-contract=off,
// so `a * b + c` below is two roundings and std::fma is one (docs/lavapipe-rules.md §1.3, §7.1).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#if defined(__x86_64__) || defined(__SSE__)
#include <xmmintrin.h>
#define RASTERCMP_HAS_MXCSR 1
#endif

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

// Denormals (docs/lavapipe-rules.md §7.10). llvmpipe runs draw_vbo (vertex fetch and shader, clip
// test, viewport, do_clip_tri, the set-up and its depth plane and offset) and its rasterizer
// threads with MXCSR FTZ (a result that would be denormal becomes a signed zero) and DAZ (a
// denormal operand of any arithmetic, comparison, min/max or conversion reads as a signed zero).
// The state-time constants (the viewport transform) are computed outside that mode.
//
// The model sets the same two hardware bits rather than flushing each operation by hand: every
// float operation of the render is affected in lavapipe, and a missed explicit flush would be a
// silent bug. Set it in every thread that does render arithmetic (render_exact, explain, the fast
// path's caller and pool jobs); the guard restores the caller's mode. Bit moves (float_bits, copies)
// are unaffected, as in lavapipe.
inline constexpr uint32_t kMxcsrFtzDaz = 0x8040u;  // FTZ (bit 15) | DAZ (bit 6)

class ScopedDenormalMode {
 public:
  explicit ScopedDenormalMode(bool flush) {
#ifdef RASTERCMP_HAS_MXCSR
    saved_ = _mm_getcsr();
    _mm_setcsr(flush ? (saved_ | kMxcsrFtzDaz) : (saved_ & ~kMxcsrFtzDaz));
#else
    (void)flush;
#endif
  }
  ~ScopedDenormalMode() {  // the mode bits only: the exception flags raised meanwhile stay (DenormalWatch)
#ifdef RASTERCMP_HAS_MXCSR
    _mm_setcsr((_mm_getcsr() & ~kMxcsrFtzDaz) | (saved_ & kMxcsrFtzDaz));
#endif
  }
  ScopedDenormalMode(const ScopedDenormalMode&) = delete;
  ScopedDenormalMode& operator=(const ScopedDenormalMode&) = delete;

 private:
  uint32_t saved_ = 0;
};

// lavapipe's draw/set-up/rasterizer mode: FTZ and DAZ on.
struct DenormalsFlushed : ScopedDenormalMode {
  DenormalsFlushed() : ScopedDenormalMode(true) {}
};
// lavapipe's state-time mode (lvp's queue thread outside draw_vbo): denormals kept.
struct DenormalsKept : ScopedDenormalMode {
  DenormalsKept() : ScopedDenormalMode(false) {}
};

// The MXCSR flags DE (a denormal operand, raised only without DAZ) and UE (a tiny result: flushed
// under FTZ, or inexact without it): whether either is raised, and clearing both. Without MXCSR
// every computation counts as having raised one.
inline constexpr uint32_t kMxcsrDenormalFlags = 0x12u;  // DE (bit 1) | UE (bit 4)
inline bool denormal_flags_raised() {
#ifdef RASTERCMP_HAS_MXCSR
  return (_mm_getcsr() & kMxcsrDenormalFlags) != 0;
#else
  return true;
#endif
}
inline void clear_denormal_flags() {
#ifdef RASTERCMP_HAS_MXCSR
  _mm_setcsr(_mm_getcsr() & ~kMxcsrDenormalFlags);
#endif
}

// Watches the calling thread's arithmetic for denormals: clears DE and UE on construction; met()
// says whether either was raised since. Under FTZ|DAZ with no denormal input, met() false means
// every intermediate was normal or zero, so the same operations without the mode give the same
// bits.
class DenormalWatch {
 public:
  DenormalWatch() { clear_denormal_flags(); }
  bool met() const { return denormal_flags_raised(); }
};

// Comparisons with 0 as code outside the denormal mode makes them (by the bits: under DAZ a
// comparison would read a denormal as 0). NaN is neither positive nor negative, as `x > 0` and
// `x < 0` say of it.
inline bool is_zero_bits(float value) { return (std::bit_cast<uint32_t>(value) & 0x7fffffffu) == 0; }
inline bool is_positive_bits(float value) {
  return !std::isnan(value) && !std::signbit(value) && !is_zero_bits(value);
}
inline bool is_negative_bits(float value) {
  return !std::isnan(value) && std::signbit(value) && !is_zero_bits(value);
}

// By its bits: under DAZ a comparison would read the value as zero.
inline bool is_denormal(float value) {
  const uint32_t bits = std::bit_cast<uint32_t>(value);
  return (bits & 0x7f800000u) == 0 && (bits & 0x007fffffu) != 0;
}

// Whether the calling thread flushes denormals (both bits set).
inline bool denormals_flushed() {
#ifdef RASTERCMP_HAS_MXCSR
  return (_mm_getcsr() & kMxcsrFtzDaz) == kMxcsrFtzDaz;
#else
  return false;
#endif
}

}  // namespace rastercmp::cpu
