// A small deterministic random source for the soak: SplitMix64 with its own uniform helpers, so
// the same seed gives the same scenes on every standard library (std::uniform_*_distribution is
// implementation-defined).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <vector>

namespace rastercmp::soak {

inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ull;
    return mix64(state_);
  }
  // Uniform in [0, 1).
  double unit() { return double(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  // Uniform integer in [lo, hi].
  int64_t range(int64_t lo, int64_t hi) { return lo + int64_t(next() % uint64_t(hi - lo + 1)); }
  bool chance(double p) { return unit() < p; }
  template <class T>
  T pick(std::initializer_list<T> values) {
    return values.begin()[range(0, int64_t(values.size()) - 1)];
  }
  template <class T>
  const T& pick(const std::vector<T>& values) {
    return values[size_t(range(0, int64_t(values.size()) - 1))];
  }

 private:
  uint64_t state_;
};

}  // namespace rastercmp::soak
