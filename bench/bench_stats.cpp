#include "bench/bench_stats.hpp"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <fstream>
#include <sstream>
#include <string>

#include "model/pixel_buffer.hpp"

namespace rastercmp::bench {
namespace {

double quantile(const std::vector<double>& sorted, double q) {
  const double position = q * double(sorted.size() - 1);
  const size_t below = size_t(position);
  const size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (sorted[above] - sorted[below]) * (position - double(below));
}

// A "Name:   1234 kB" line of /proc/self/status, in bytes; 0 when absent.
uint64_t status_bytes(const std::string& name) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(name + ":", 0) != 0) continue;
    std::istringstream fields(line.substr(name.size() + 1));
    uint64_t kib = 0;
    fields >> kib;
    return kib * 1024;
  }
  return 0;
}

bool reset_peak_rss() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return bool(clear);
}

uint64_t max_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return uint64_t(usage.ru_maxrss) * 1024;
}

double own_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// Busy (non-idle, non-iowait) ticks of all CPUs from /proc/stat.
uint64_t machine_busy_ticks() {
  std::ifstream stat("/proc/stat");
  std::string cpu;
  uint64_t user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  stat >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
  return user + nice + system + irq + softirq + steal;
}

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

TimingStats summarize(std::vector<double> seconds) {
  TimingStats stats;
  if (seconds.empty()) return stats;
  std::sort(seconds.begin(), seconds.end());
  stats.count = seconds.size();
  stats.min = seconds.front();
  stats.max = seconds.back();
  stats.median = quantile(seconds, 0.5);
  stats.q1 = quantile(seconds, 0.25);
  stats.q3 = quantile(seconds, 0.75);
  return stats;
}

long page_fault_count() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt + usage.ru_majflt;
}

bool keep_freed_memory() {
  // mallopt returns 1 when it took the setting (glibc), 0 otherwise (ASan's interceptor)
  const bool trim = mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
  const bool mapped = mallopt(M_MMAP_THRESHOLD, kKeptBlockBytes) == 1;
  return trim && mapped;
}

uint64_t peak_memory_delta(const std::function<void()>& run) {
  release_kept_blocks();  // the run's own memory, none of it kept from earlier frees (pixel_buffer.hpp)
  malloc_trim(0);
  if (reset_peak_rss()) {
    const uint64_t before = status_bytes("VmRSS");
    run();
    const uint64_t peak = status_bytes("VmHWM");
    return peak > before ? peak - before : 0;
  }
  const uint64_t before = max_rss_bytes();
  run();
  const uint64_t after = max_rss_bytes();
  return after > before ? after - before : 0;
}

void LoadMonitor::start() {
  busy_ticks_ = machine_busy_ticks();
  own_cpu_ = own_cpu_seconds();
  start_wall_ = now_seconds();
}

void LoadMonitor::stop() {
  wall_ = now_seconds() - start_wall_;
  const double ticks_per_second = double(sysconf(_SC_CLK_TCK));
  const double machine = double(machine_busy_ticks() - busy_ticks_) / ticks_per_second;
  const double own = own_cpu_seconds() - own_cpu_;
  own_ = wall_ > 0 ? own / wall_ : 0;
  other_ = wall_ > 0 ? std::max(0.0, machine - own) / wall_ : 0;
  std::ifstream loadavg("/proc/loadavg");
  loadavg >> load1_;
}

}  // namespace rastercmp::bench
