// "Model no more than a scene needs" (issue 21 item 5): which pipeline stages a scene's state
// requires, read from the scene alone. Each stage names the exact path's work skip that leaves its
// work out when the scene does not need it (cpu_raster/exact/work_skips.hpp; docs/cpu-raster.md
// "What each skip buys"), or none where the exact path has no such work to leave out.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cpu_raster/cpu_raster.hpp"
#include "model/scene.hpp"

namespace rastercmp::experiments {

struct StageNeeds {
  bool clipping = false;  // some vertex a primitive uses lies outside a tested clip plane (rules §1.5)
  bool depth = false;     // a depth attachment and some draw with the depth test on
  bool bias = false;      // some draw with depth bias on and a non-zero factor (§4.3)
  bool msaa = false;      // more than one sample per pixel
  bool lines = false;     // some draw of lines (line topology or polygon mode line)
  bool culling = false;   // some draw with a cull mode other than none
};

StageNeeds scene_needs(const Scene& scene);

struct StageInfo {
  std::string name;  // clipping, depth, bias, msaa, lines, culling
  bool (*needed)(const StageNeeds&);
  // The skip that turns this stage's work back on (nullopt: none, the path has no work to skip).
  std::optional<std::string> skip;
};
const std::vector<StageInfo>& pipeline_stages();

// The options with one work skip turned off ("clip", "depth", "bias"; "all": the three).
// Throws std::invalid_argument for another name.
CpuOptions with_skip_off(CpuOptions options, const std::string& skip);

}  // namespace rastercmp::experiments
