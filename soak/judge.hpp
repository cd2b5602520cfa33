// How the soak and the reducer judge one scene: CaseRunner's verdict, reduced to a failure kind
// that "fails the same way" compares (docs/soak.md "Failure kinds").
#pragma once

#include <string>

#include "compare/case_result.hpp"
#include "compare/case_run.hpp"
#include "model/scene.hpp"

namespace rastercmp::soak {

// "" when the scene does not fail (Pass, QualityWarning, NotSupported); else "coverage" (a Fail
// with coverage differences), "depth" (a Fail with depth differences only), or the verdict name
// and the message up to its first ':' for the error verdicts ("InternalError: device"), or
// "InternalError: validation" when the validation layer spoke.
std::string failure_kind(const CaseResult& result);

// TEST-ONLY broken model. When the environment variable RASTERCMP_TEST_BREAK_MODEL is
// "drop_right", the CPU (expected) render of every judged scene loses the samples of each
// primitive whose first vertex has clip x / w > 0.25, and the diff and verdict are recomputed.
// It exists so that tests/test_soak.cpp can check that the soak finds and the reducer shrinks a
// known model bug; it is read here, after rendering, never inside a renderer. Any other value
// is an error (std::invalid_argument).
bool break_model_enabled();
void apply_break_model(const Scene& scene, CaseResult& result, CompareProfile profile);

// Renders the scene on both backends (runner.run), applies the test-only broken model when it
// is enabled, and returns the result.
CaseResult judge(CaseRunner& runner, const Scene& scene);

}  // namespace rastercmp::soak
