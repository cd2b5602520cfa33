// libFuzzer main for the scene parser (fuzz/fuzz_checks.hpp).
#include "fuzz/fuzz_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rastercmp::fuzz::check_scene_parser(data, size);
  return 0;
}
