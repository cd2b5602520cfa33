#include "cpu_raster/fast/cpu_features.hpp"

#include <cstdlib>
#include <cstring>

namespace rastercmp::cpu::fast {
namespace {

// RASTERCMP_FAST_KERNELS=scalar|avx2 caps the kernels the host runs (anything else: no cap).
int kernel_cap() {
  static const int cap = [] {
    const char* env = std::getenv("RASTERCMP_FAST_KERNELS");
    if (env && std::strcmp(env, "scalar") == 0) return 0;
    if (env && std::strcmp(env, "avx2") == 0) return 1;
    return 2;
  }();
  return cap;
}

}  // namespace

bool host_has_avx2_fma() {
  static const bool has = [] {
    __builtin_cpu_init();
    return kernel_cap() >= 1 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return has;
}

bool host_has_avx512() {
  static const bool has = [] {
    __builtin_cpu_init();
    return kernel_cap() >= 2 && host_has_avx2_fma() && __builtin_cpu_supports("avx512f") &&
           __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512dq");
  }();
  return has;
}

}  // namespace rastercmp::cpu::fast
