// The one list of the stages and method names `--method STAGE=NAME` (and a scene's "methods")
// accepts: what each does in one line, the lecture notes' section it comes from (by title), the
// docs/methods.md section that describes it, and whether it can run on a given scene. `rastercmp
// methods`, `--help`, option validation, parse_classic_methods / parse_setup_methods and the
// README's list (tests/test_method_registry.cpp) all read it.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/scene.hpp"

namespace rastercmp::cpu::classic {

struct StageInfo {
  std::string_view stage;
  std::string_view summary;
};

struct MethodInfo {
  std::string_view stage;
  std::string_view name;
  std::string_view summary;  // one line
  std::string_view notes;    // the lecture notes' section title(s); empty for lavapipe's own rule
  std::string_view doc;      // docs/methods.md (or docs/cpu-raster.md) section that describes it
};

// Stages in pipeline order: clip, cull, fill, line, depth, visibility, then the exact path's
// set-up ablations snap and tie_break.
const std::vector<StageInfo>& method_stages();

// Every accepted (stage, name), grouped by stage in method_stages() order, the default first.
const std::vector<MethodInfo>& method_registry();

// nullptr when the pair is not in the registry.
const MethodInfo* find_method(std::string_view stage, std::string_view name);

// "a, b, c": the accepted names of a stage (empty for an unknown stage); all stages likewise.
std::string method_names(std::string_view stage);
std::string stage_names();

// Throws UsageError naming the known stages, or the known names of the stage.
void check_method_choice(const MethodChoice& choice);

// Why the chosen method cannot run on the scene, naming the scene's feature (its sample count, a
// draw's topology, line width or vertex w), or nullopt when it can. Unknown names: nullopt.
std::optional<std::string> method_inapplicable(const Scene& scene, const MethodChoice& choice);

// The far plane of a pseudo_depth_* name (75, 750, 7500), 0 for other names. The near plane is
// always the notes' 25.
double pseudo_depth_far(std::string_view name);
inline constexpr double kPseudoDepthNear = 25;

// Eye-space distance of one stored depth step at the far plane, for a depth format of `bits`
// unorm bits: (far - near) far / (near (2^bits - 1)).
double pseudo_depth_step_at_far(double far_distance, int bits);

}  // namespace rastercmp::cpu::classic
