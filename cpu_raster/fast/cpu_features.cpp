#include "cpu_raster/fast/cpu_features.hpp"

namespace rastercmp::cpu::fast {

bool host_has_avx2_fma() {
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return has;
}

bool host_has_avx512() {
  static const bool has = [] {
    __builtin_cpu_init();
    return host_has_avx2_fma() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
           __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  }();
  return has;
}

}  // namespace rastercmp::cpu::fast
