// Run-time dispatch for the fast path's SIMD kernels (docs/performance.md): the kernels are
// compiled with __attribute__((target(...))) and called only when the host has the
// instructions; every kernel has a scalar twin that gives the same bits.
#pragma once

#define RASTERCMP_AVX2 __attribute__((target("avx2,fma")))
#define RASTERCMP_AVX512 __attribute__((target("avx2,fma,avx512f,avx512vl,avx512bw,avx512dq")))

namespace rastercmp::cpu::fast {

// The host executes AVX2 and FMA3 instructions (__builtin_cpu_supports), and
// RASTERCMP_FAST_KERNELS is not "scalar".
bool host_has_avx2_fma();

// The host also executes AVX-512 F, VL, BW and DQ instructions, and RASTERCMP_FAST_KERNELS is
// neither "scalar" nor "avx2" (the variable lets a host whose 512-bit operations cost more than
// two 256-bit ones, or lower the clock, run the AVX2 kernels: docs/performance.md).
bool host_has_avx512();

}  // namespace rastercmp::cpu::fast
