// Facts about the host CPU that decide lavapipe's arithmetic (docs/lavapipe-rules.md §1.3, §7.1).
#pragma once

namespace rastercmp {

// The host CPU executes fused multiply-add (CPUID FMA3 with OS-enabled AVX state).
bool host_cpu_has_fma();

// lavapipe on this host fuses llvm.fmuladd: the host has FMA and GALLIUM_OVERRIDE_CPU_CAPS does not
// turn AVX off (any override naming a level below avx2, e.g. "sse4.1", disables FMA).
bool lavapipe_fuses_on_this_host();

}  // namespace rastercmp
