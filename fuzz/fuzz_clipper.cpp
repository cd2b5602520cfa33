// libFuzzer main for the triangle clipper (fuzz/fuzz_checks.hpp).
#include "fuzz/fuzz_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rastercmp::fuzz::check_clipper(data, size);
  return 0;
}
