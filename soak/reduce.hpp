// Automatic reduction (docs/soak.md "Reduction"): delta debugging on a failing scene, in the
// manner of C-Reduce. Each pass proposes a smaller or simpler scene and keeps it only when
// `still_fails` says it still fails the same way; passes repeat until none makes progress:
//   drop draws (ddmin) · unroll strips, fans and indices into plain lists · drop primitives
//   (ddmin) · drop unused positions · reset scene state (scissor, viewport, samples, depth
//   format and clear) and draw state (cull, face, modes, width, depth test, bias, clamp, clip)
//   to the defaults · move vertices to w = 1 and onto whole, half, 1/16 and 1/256 pixels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "model/scene.hpp"

namespace rastercmp::soak {

using StillFails = std::function<bool(const Scene&)>;

struct ReduceStats {
  size_t runs = 0;  // calls of still_fails
  bool hit_limit = false;
  uint64_t primitives_before = 0, primitives_after = 0;
  size_t draws_before = 0, draws_after = 0;
};

// `max_runs` bounds the calls of still_fails; the best scene found so far is returned.
Scene reduce_scene(const Scene& scene, const StillFails& still_fails, size_t max_runs, ReduceStats* stats = nullptr);

}  // namespace rastercmp::soak
