// Method switches of the exact path's set-up, chosen by data (--method STAGE=NAME or a scene's
// "methods"). They exist to prove that the differential check can fail: each one replaces a rule
// lavapipe follows with a classic alternative. The inner loop never looks at them.
#pragma once

#include <vector>

#include "cpu_raster/exact/fixed_point.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

// Which edges get the +1 on their constant so that "E > 0" covers samples on them.
enum class TieBreak {
  TopLeft,  // lavapipe: left edges and the top edge are inclusive (rules §2.4)
  None,     // ablation "none": no edge is inclusive, samples exactly on an edge are dropped
};

struct SetupMethods {
  SnapRounding snap = SnapRounding::NearestEven;
  TieBreak tie_break = TieBreak::TopLeft;
};

// Stages and names this path understands:
//   snap      = round_nearest_even (default) | round_half_away
//   tie_break = top_left (default)           | none
// Throws UsageError naming the stage or name it does not know.
SetupMethods parse_setup_methods(const std::vector<MethodChoice>& choices);

}  // namespace rastercmp::cpu
