#include "model/host.hpp"

#include <cpuid.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>
#include <thread>

namespace rastercmp {

bool host_cpu_has_fma() {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
  const bool fma = ecx & bit_FMA;
  const bool osxsave = ecx & bit_OSXSAVE;
  if (!fma || !osxsave) return false;
  // The OS must save the YMM state (XCR0 bits 1 and 2), or AVX/FMA instructions fault.
  unsigned xcr0_lo = 0, xcr0_hi = 0;
  __asm__ volatile("xgetbv" : "=a"(xcr0_lo), "=d"(xcr0_hi) : "c"(0));
  return (xcr0_lo & 0x6) == 0x6;
}

bool lavapipe_fuses_on_this_host() {
  if (!host_cpu_has_fma()) return false;
  // util/u_cpu_detect.c check_cpu_caps_override: the names below clear AVX and hence FMA.
  const char* override_caps = std::getenv("GALLIUM_OVERRIDE_CPU_CAPS");
  if (override_caps == nullptr) return true;
  const std::string_view caps(override_caps);
  return !(caps == "nosse" || caps == "sse" || caps == "sse2" || caps == "sse3" || caps == "ssse3" || caps == "sse4.1");
}

std::string cpu_model_from_cpuinfo(const std::string& cpuinfo) {
  std::istringstream in(cpuinfo);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const size_t start = line.find_first_not_of(" \t", colon + 1);
    if (start != std::string::npos) return line.substr(start);
  }
  return "unknown";
}

std::string host_cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::ostringstream text;
  text << in.rdbuf();
  return cpu_model_from_cpuinfo(text.str());
}

uint32_t host_usable_cpus() {
#ifdef __linux__
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) == 0 && CPU_COUNT(&allowed) > 0)
    return uint32_t(CPU_COUNT(&allowed));
#endif
  return std::max(1u, std::thread::hardware_concurrency());
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

double thread_cpu_clock_cost() {
  static const double cost = [] {
    double least = 1.0;
    for (int i = 0; i < 64; ++i) {
      const double a = thread_cpu_seconds();
      least = std::min(least, thread_cpu_seconds() - a);
    }
    return std::max(least, 0.0);
  }();
  return cost;
}

}  // namespace rastercmp
