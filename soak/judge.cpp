#include "soak/judge.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "compare/diff.hpp"
#include "compare/verdict.hpp"
#include "soak/primitives.hpp"

namespace rastercmp::soak {

std::string failure_kind(const CaseResult& result) {
  if (!is_failure(result.verdict)) return "";
  if (result.verdict == Verdict::Fail) {
    if (result.diff && result.diff->summary.coverage_mismatches() > 0) return "coverage";
    return "depth";
  }
  // Validation messages: their count varies as the scene shrinks, so the kind leaves it out.
  if (!result.validation_messages.empty()) return std::string(to_string(result.verdict)) + ": validation";
  const auto colon = result.message.find(':');
  return std::string(to_string(result.verdict)) + ": " + result.message.substr(0, colon);
}

bool break_model_enabled() {
  const char* value = std::getenv("RASTERCMP_TEST_BREAK_MODEL");
  if (value == nullptr || *value == '\0') return false;
  if (std::string(value) == "drop_right") return true;
  throw std::invalid_argument(std::string("RASTERCMP_TEST_BREAK_MODEL: expected \"drop_right\", found \"") + value +
                              "\"");
}

void apply_break_model(const Scene& scene, CaseResult& result, CompareProfile profile) {
  if (!result.expected || !result.actual) return;
  RenderResult& cpu = *result.expected;
  bool changed = false;
  for (uint32_t& owner : cpu.owner) {
    if (owner == kOwnerBackground) continue;
    const uint32_t d = owner_draw(owner);
    if (d >= scene.draws.size()) continue;
    const Draw& draw = scene.draws[d];
    const std::vector<uint32_t> v = primitive_vertices(draw, owner_primitive(owner));
    const glm::vec4 first = draw.positions_clip[v.front()];
    if (first.w != 0 && first.x / first.w > 0.25f) {
      owner = kOwnerBackground;
      changed = true;
    }
  }
  if (!changed) return;
  result.diff = diff_results(*result.expected, *result.actual, profile);
  const VerdictDecision decision = decide_verdict(result.diff->summary, spec_depth_tolerance_r(scene));
  result.verdict = decision.verdict;
  result.message = decision.message + " (test-only broken model drop_right)";
}

CaseResult judge(CaseRunner& runner, const Scene& scene) {
  CaseResult result = runner.run(scene);
  if (break_model_enabled() && result.validation_messages.empty()) apply_break_model(scene, result, runner.profile());
  return result;
}

}  // namespace rastercmp::soak
