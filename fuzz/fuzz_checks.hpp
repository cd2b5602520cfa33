// The bodies of the fuzz targets, shared by the libFuzzer mains (fuzz_*.cpp, `make fuzz`) and
// by tests/test_fuzz_regressions.cpp, which replays every input in fuzz/regressions/.
// Each aborts on a violated property, so a fuzzer reports it and a regression test crashes.
#pragma once

#include <cstddef>
#include <cstdint>

namespace rastercmp::fuzz {

// Any bytes → parse_scene returns a Scene or throws InputError; small scenes are then rendered
// on the CPU path, which may only throw NotSupportedError.
void check_scene_parser(const uint8_t* data, size_t size);

// 12 floats (three clip-space vertices, any bits) + 2 flag bytes → the lavapipe clipper: no
// crash, an inside triangle passes unchanged, an outside one vanishes, at most 7 triangles.
void check_clipper(const uint8_t* data, size_t size);

}  // namespace rastercmp::fuzz
