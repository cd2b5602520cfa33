// What one case produced: its verdict and message, the two renders when they succeeded and their
// diff. Plain data: the report and the records read it without knowing the renderers.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "compare/diff.hpp"
#include "compare/verdict.hpp"
#include "model/render_result.hpp"

namespace rastercmp {

struct CaseResult {
  Verdict verdict = Verdict::InternalError;
  std::string message;
  std::optional<RenderResult> expected;  // the CPU render, when it succeeded
  std::optional<RenderResult> actual;    // the Vulkan render, when it succeeded
  std::optional<SceneDiff> diff;         // when both succeeded
  std::vector<std::string> validation_messages;
  std::string cpu_method = "exact";  // cpu_method_label of the CPU options used
};

}  // namespace rastercmp
