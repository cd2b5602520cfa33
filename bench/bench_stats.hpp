// Measurement helpers of the benchmarks (docs/performance.md, "How to measure"): robust summaries of
// repeated timings, per-run peak memory and the machine's load during a run.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace rastercmp::bench {

struct TimingStats {
  size_t count = 0;
  double median = 0, q1 = 0, q3 = 0, min = 0, max = 0;  // seconds
};

// Quartiles by linear interpolation between order statistics; all zero for no samples.
TimingStats summarize(std::vector<double> seconds);

// Makes the process keep the memory it frees for its next allocations instead of handing it back
// to the kernel (glibc's allocator, every arena: no trimming of a heap's free top, and blocks up to
// kKeptBlockBytes from the heaps instead of mappings of their own, a fixed threshold), so that a
// timed render does not pay first touches of pages the render before it freed, which on a shared
// VM cost 10-35 us each (lavapipe's grid_180k on the Zen 5 host: docs/performance-log.md,
// "Lavapipe's page faults; what a band unit costs"). The fast path keeps its attachments itself
// (model/pixel_buffer.hpp). False where the allocator refuses the settings (ASan's ignores them).
inline constexpr int kKeptBlockBytes = 32 << 20;  // glibc's largest mmap threshold on 64-bit hosts
bool keep_freed_memory();

// The process's page faults so far (all its threads; minor ones: a first touch of a page).
long page_fault_count();

// Peak resident memory a call adds above what the process held when it started, in bytes, with
// no freed attachment blocks kept from before it (release_kept_blocks, model/pixel_buffer.hpp) and
// the allocator's free memory handed back first (malloc_trim: kept by keep_freed_memory, it would
// be reused by the call without adding to the resident memory).
// Uses Linux's resettable high-water mark (/proc/self/clear_refs "5", VmHWM); where that is not
// available, the growth of getrusage ru_maxrss (0 when an earlier peak was higher).
uint64_t peak_memory_delta(const std::function<void()>& run);

// CPU time of the whole machine against this process's own, between start() and stop():
// `other_cores` is how many cores other processes kept busy on average (the noise).
class LoadMonitor {
 public:
  void start();
  void stop();
  double wall_seconds() const { return wall_; }
  double own_cores() const { return own_; }
  double other_cores() const { return other_; }
  double load_average_1min() const { return load1_; }

 private:
  uint64_t busy_ticks_ = 0;
  double own_cpu_ = 0, start_wall_ = 0;
  double wall_ = 0, own_ = 0, other_ = 0, load1_ = 0;
};

}  // namespace rastercmp::bench
