// What the Lavapipe profile reproduces, checked before any work (docs/cpu-raster.md "Not
// supported"). State lavapipe renders through paths this model does not contain raises
// NotSupportedError; a scene that breaks the model's preconditions (built in code rather than
// loaded, which the loader would have refused) raises InputError.
#pragma once

#include "model/scene.hpp"

namespace rastercmp::cpu {

void check_lavapipe_profile_support(const Scene& scene);

}  // namespace rastercmp::cpu
