// Run-time dispatch for the fast path's AVX2 kernels (docs/performance.md): the kernels are
// compiled with __attribute__((target("avx2,fma"))) and called only when the host has both;
// every kernel has a scalar twin that gives the same bits.
#pragma once

#define RASTERCMP_AVX2 __attribute__((target("avx2,fma")))

namespace rastercmp::cpu::fast {

// The host executes AVX2 and FMA3 instructions (__builtin_cpu_supports).
bool host_has_avx2_fma();

}  // namespace rastercmp::cpu::fast
