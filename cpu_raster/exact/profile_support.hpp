// What the Lavapipe profile reproduces, checked before any work (docs/cpu-raster.md "Not
// supported"). State lavapipe renders through paths this model does not contain raises
// NotSupportedError; a scene that breaks the model's preconditions (built in code rather than
// loaded, which the loader would have refused) raises InputError.
#pragma once

#include "model/scene.hpp"

namespace rastercmp::cpu {

void check_lavapipe_profile_support(const Scene& scene);

// The same checks but the index scans: with indices_in_range true for every draw, the scene passes
// check_lavapipe_profile_support. For a caller that reads the indices anyway (the fast path's
// block-row phase) and calls check_lavapipe_profile_support when one is out of range, so that the
// error is the one the full check names first. Throws what check_lavapipe_profile_support throws.
void check_lavapipe_profile_support_but_indices(const Scene& scene);

// Every index of the draw names one of its positions.
bool indices_in_range(const Draw& draw);

}  // namespace rastercmp::cpu
