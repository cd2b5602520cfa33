// Facts about the host CPU: those that decide lavapipe's arithmetic (docs/lavapipe-rules.md §1.3,
// §7.1), and those a measurement records (its CPU model, a thread's CPU clock).
#pragma once

#include <cstdint>
#include <string>

namespace rastercmp {

// The host CPU executes fused multiply-add (CPUID FMA3 with OS-enabled AVX state).
bool host_cpu_has_fma();

// lavapipe on this host fuses llvm.fmuladd: the host has FMA and GALLIUM_OVERRIDE_CPU_CAPS does not
// turn AVX off (any override naming a level below avx2, e.g. "sse4.1", disables FMA).
bool lavapipe_fuses_on_this_host();

// The first "model name" of a /proc/cpuinfo text ("unknown" when there is none).
std::string cpu_model_from_cpuinfo(const std::string& cpuinfo);

// This host's CPU model, from /proc/cpuinfo ("unknown" where it cannot be read).
std::string host_cpu_model();

// The CPUs this process may run on: its affinity mask (`taskset`, a container's cpuset), at least 1;
// the hardware threads where the mask cannot be read. A measurement on N workers is a measurement
// on N cores only up to this number.
uint32_t host_usable_cpus();

// The calling thread's CPU time in seconds (CLOCK_THREAD_CPUTIME_ID).
double thread_cpu_seconds();

// What an interval timed with thread_cpu_seconds() holds of the clock's own cost: the least of 64
// intervals between back-to-back calls, measured once (a system call: 0.5 us on the 2-vCPU Zen 5
// VM of docs/performance.md).
double thread_cpu_clock_cost();

}  // namespace rastercmp
