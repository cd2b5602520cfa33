#include "compare/verdict.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "compare/depth_units.hpp"
#include "model/depth_format.hpp"

namespace rastercmp {
namespace {

constexpr Verdict kAllVerdicts[] = {Verdict::Pass,         Verdict::Fail,          Verdict::QualityWarning,
                                    Verdict::NotSupported, Verdict::ResourceError, Verdict::InternalError,
                                    Verdict::Crash,        Verdict::Timeout};

// Spec "Depth Bias": interpolation precision is implementation-dependent; 2 r is one UNORM
// conversion step either way plus one more, and one float binade step either way.
constexpr double kSpecDepthBaseToleranceR = 2.0;

// Named from the judged side: the diff's missing is a sample the CPU render has and the device
// lacks, so when a classic CPU method is judged it is a sample the method adds (docs/compare.md
// "Who is judged").
std::string coverage_counts(const DiffSummary& d, Judged judged) {
  if (judged == Judged::CpuMethod)
    return fmt::format("{} the method lacks, {} the method adds, {} wrong owner", d.unexpected, d.missing,
                       d.wrong_owner);
  return fmt::format("{} missing, {} unexpected, {} wrong owner", d.missing, d.unexpected, d.wrong_owner);
}

std::string depth_counts(const DiffSummary& d) {
  return fmt::format("{} depth mismatches, max {} {} ({:.6g} r) at ({}, {}) sample {}", d.depth.mismatches,
                     d.depth.max_raw, depth_unit_name(d.depth_format), d.depth.max_r, d.depth.max_at.x,
                     d.depth.max_at.y, d.depth.max_at.sample);
}

VerdictDecision decide_lavapipe(const DiffSummary& d, Judged judged) {
  // The lavapipe profile claims bit-exactness: any difference fails (docs/lavapipe-rules.md "Tolerances").
  if (d.coverage_mismatches() == 0 && d.depth.mismatches == 0) return {Verdict::Pass, "bit-exact"};
  std::string why = coverage_counts(d, judged);
  if (d.depth.mismatches != 0) why += "; " + depth_counts(d);
  return {Verdict::Fail, why};
}

std::string depth_value(DepthFormat format, uint32_t raw) {
  return fmt::format("{:.9g} (raw {})", depth_raw_to_value(format, raw), raw);
}

std::string outside_counts(const DiffSummary& d) {
  const DepthViolation& v = d.worst_outside;
  return fmt::format(
      "{} samples store a depth outside the spec interval; farthest at ({}, {}) sample {}: {} is {} {} {} by {} "
      "{}, a bound set by {}",
      d.depth_outside, v.at.x, v.at.y, v.at.sample, depth_value(d.depth_format, v.actual_raw),
      v.above ? "above" : "below", v.above ? "hi" : "lo", depth_value(d.depth_format, v.bound_raw), v.distance,
      depth_unit_name(d.depth_format), to_string(v.term));
}

// The May samples, and the Must samples owned by another primitive as an exact device may own them.
std::string allowed_counts(const DiffSummary& d) {
  std::string text = fmt::format("{} allowed (may)", d.allowed);
  if (d.allowed_owner != 0)
    text += fmt::format(
        ", {} allowed owner (another primitive, as a device computing the spec's equations exactly leaves it with "
        "other choices the spec leaves open: vertex rounding, tie rule, depth bias r and m, D32 rounding)",
        d.allowed_owner);
  return text;
}

VerdictDecision decide_spec(const DiffSummary& d, double tolerance_r, Judged judged) {
  const std::string allowed = allowed_counts(d);
  if (d.missing + d.unexpected != 0) {
    std::string why = coverage_counts(d, judged) + ", " + allowed;
    if (d.depth_outside != 0) why += "; " + outside_counts(d);
    return {Verdict::Fail, why};
  }
  if (d.depth_outside != 0) return {Verdict::Fail, outside_counts(d) + "; " + coverage_counts(d, judged) + ", " + allowed};
  if (d.wrong_owner != 0 && d.depth_intervals_checked)
    return {Verdict::QualityWarning,
            coverage_counts(d, judged) +
                " (owners no device computing the spec's equations exactly leaves there: only arithmetic precision "
                "decides which primitive wins, which the spec leaves to quality, e.g. between coplanar primitives; "
                "every stored depth lies inside its spec interval), " +
                allowed};
  if (d.wrong_owner != 0)
    return {Verdict::QualityWarning, coverage_counts(d, judged) + " (the spec does not fix which primitive wins), " + allowed};
  if (d.depth_intervals_checked)
    return {Verdict::Pass,
            fmt::format("within the spec: {}, every stored depth inside its spec interval ({} differ from the lavapipe "
                        "estimate, max {} {})",
                        allowed, d.depth.mismatches, d.depth.max_raw, depth_unit_name(d.depth_format))};
  if (d.depth.max_r > tolerance_r)
    return {Verdict::QualityWarning, fmt::format("{} (tolerance {:.6g} r), {}", depth_counts(d), tolerance_r, allowed)};
  return {Verdict::Pass, fmt::format("within the spec: {}, {} depth differences within {:.6g} r", allowed,
                                     d.depth.mismatches, tolerance_r)};
}

}  // namespace

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::Pass: return "Pass";
    case Verdict::Fail: return "Fail";
    case Verdict::QualityWarning: return "QualityWarning";
    case Verdict::NotSupported: return "NotSupported";
    case Verdict::ResourceError: return "ResourceError";
    case Verdict::InternalError: return "InternalError";
    case Verdict::Crash: return "Crash";
    case Verdict::Timeout: return "Timeout";
  }
  return "?";
}

std::optional<Verdict> parse_verdict(std::string_view name) {
  for (Verdict v : kAllVerdicts)
    if (name == to_string(v)) return v;
  return std::nullopt;
}

bool is_failure(Verdict v) {
  return v == Verdict::Fail || v == Verdict::ResourceError || v == Verdict::InternalError || v == Verdict::Crash ||
         v == Verdict::Timeout;
}

double spec_depth_tolerance_r(const Scene& scene) {
  double largest_constant = 0;
  for (const Draw& draw : scene.draws)
    if (draw.state.depth_bias.enable)
      largest_constant = std::max(largest_constant, std::fabs(double(draw.state.depth_bias.constant_factor)));
  // UNORM r ranges over [2^-n, 2 * 2^-n]; in units of lavapipe's r = 2/(2^n - 1) that span is 1/2.
  const bool unorm = is_unorm(scene.depth_format);
  return kSpecDepthBaseToleranceR + (unorm ? 0.5 * largest_constant : 0.0);
}

VerdictDecision decide_verdict(const DiffSummary& diff, double depth_tolerance_r, Judged judged) {
  VerdictDecision decision = diff.profile == CompareProfile::Lavapipe ? decide_lavapipe(diff, judged)
                                                                      : decide_spec(diff, depth_tolerance_r, judged);
  if (diff.depth_format != DepthFormat::None && !diff.depth_compared)
    decision.message +=
        "; depth not compared (one render carries none, e.g. multisampled depth on a device that cannot sample it)";
  return decision;
}

}  // namespace rastercmp
