// A scene's verdict, named as the Vulkan CTS names test results (qpTestLog.c
// s_qpTestResultMap), and the rule that turns a diff into one (docs/compare.md "Verdicts").
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "compare/diff.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Crash and Timeout are given by the conformance runner, not by a diff: the case's child process
// died or ran past --timeout (CTS: the test process died or its watchdog fired).
enum class Verdict { Pass, Fail, QualityWarning, NotSupported, ResourceError, InternalError, Crash, Timeout };

const char* to_string(Verdict);
std::optional<Verdict> parse_verdict(std::string_view name);

// Fail, ResourceError, InternalError, Crash and Timeout; Pass, QualityWarning and NotSupported are not failures
// (as in the CTS, where a warning or an unsupported feature does not fail a run).
bool is_failure(Verdict);

struct VerdictDecision {
  Verdict verdict = Verdict::Pass;
  std::string message;  // one line: why
};

// Spec profile depth tolerance in units of r:
//   2 r (interpolation and conversion rounding the spec leaves open, 1 LSB of UNORM = r/2)
//   + |constantFactor| * (r_max - r_min) of the scene's biased draws: the spec lets a UNORM
//   format's r lie anywhere in [2^-n, 2 * 2^-n] (CTS depth_bias_control threshold), which is
//   half of lavapipe's r = 2/(2^n - 1); float formats have one r.
double spec_depth_tolerance_r(const Scene& scene);

// Lavapipe profile: Pass only with 0 coverage and 0 depth differences, else Fail.
// Spec profile: Fail on any missing (Must) or unexpected (MustNot) sample, or, when the expected
// render carries depth intervals, on any Must or May sample whose stored depth lies outside its
// interval (the message names the farthest one, the bound it broke and the term that set it). A
// wrong owner (a Must sample owned by a primitive no exactly computing device leaves there) is a
// QualityWarning: only arithmetic precision decides that winner. An allowed owner (one such a
// device leaves there, RenderResult::owner_alternatives) is a Pass. Without intervals a depth
// difference beyond `depth_tolerance_r` is a QualityWarning. May samples never count for coverage.
// `judged` names the coverage counts of the message: the device's missing / unexpected, or, when a
// classic CPU method is judged against the device, what the method lacks / adds.
enum class Judged { Device, CpuMethod };
VerdictDecision decide_verdict(const DiffSummary& diff, double depth_tolerance_r, Judged judged = Judged::Device);

}  // namespace rastercmp
