// Per-sample comparison of two renders of one scene: the CPU render is the expected result
// (the reference model), the Vulkan render the actual one. Pure: two RenderResults in, counts,
// depth statistics, the first bad samples and per-sample classes out (docs/compare.md).
//
// Coverage (owner ids):
//   missing      expected covered, actual background
//   unexpected   actual covered, expected background
//   wrong_owner  both covered, by different draws/primitives
//   allowed      spec profile only: any difference on a sample the CPU classed May
//   allowed_owner spec profile only: a Must sample owned by another primitive that a device
//                computing the spec's equations exactly, with other choices the spec leaves open,
//                leaves there (RenderResult::owner_alternatives, docs/spec-profile.md "Owners")
// Spec profile: coverage is judged against RenderResult::coverage_class of the expected
// render (Must / May / MustNot, tcuRasterizationVerifier's FULL / PARTIAL / NONE); an empty
// coverage_class is read as Must where the expected render covers and MustNot elsewhere.
// Depth: compared only on samples whose coverage agrees (same owner, or both background), so a
// coverage difference is never counted twice, and only when both renders carry depth (the
// Vulkan reference carries none for a multisampled format its device cannot sample).
// Spec profile with RenderResult::depth_interval: the stored depth of every Must and May sample is
// checked against its interval, whatever the owners, except where the coverage already fails
// ("depth_outside", docs/spec-profile.md).
// Units: compare/depth_units.hpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "model/render_result.hpp"

namespace rastercmp {

enum class CompareProfile { Lavapipe, Spec };
const char* to_string(CompareProfile);

enum class SampleClass : uint8_t { Background, Correct, Missing, Unexpected, WrongOwner, Allowed, AllowedOwner };
const char* to_string(SampleClass);

// How many bad samples a diff keeps, in scan order (y, then x, then sample).
inline constexpr size_t kMaxBadSamples = 16;

struct SampleLocation {
  uint32_t x = 0, y = 0, sample = 0;
  bool operator==(const SampleLocation&) const = default;
};

// One sample that differs: its coverage class ("missing", "unexpected", "wrong_owner"),
// "depth_outside" when its stored depth is outside its spec interval, or "depth" when the coverage
// agrees and only the stored depth differs.
struct BadSample {
  SampleLocation at;
  std::string kind;
  uint32_t expected_owner = kOwnerBackground, actual_owner = kOwnerBackground;
  bool has_depth = false;
  uint32_t expected_depth_raw = 0, actual_depth_raw = 0;
  uint64_t depth_diff_raw = 0;  // in depth_unit_name() units
  double depth_diff_r = 0;      // in units of r
  bool operator==(const BadSample&) const = default;
};

// Statistics over the samples whose coverage agrees and whose raw depth differs.
// Percentiles are nearest-rank over those samples only (0 when there are none).
struct DepthStats {
  uint64_t mismatches = 0;
  uint64_t p50_raw = 0, p95_raw = 0, max_raw = 0;
  double p50_r = 0, p95_r = 0, max_r = 0;
  SampleLocation max_at;
  uint32_t max_expected_raw = 0, max_actual_raw = 0;
  bool operator==(const DepthStats&) const = default;
};

// Spec profile: the sample whose stored depth lies farthest outside its spec interval
// (RenderResult::depth_interval), in depth_unit_name() units; the first in scan order wins ties.
struct DepthViolation {
  SampleLocation at;
  uint32_t actual_raw = 0, bound_raw = 0;
  bool above = false;                 // past the upper bound hi (else below lo)
  DepthTerm term = DepthTerm::Plane;  // what dominated the bound it broke
  uint64_t distance = 0;
  bool operator==(const DepthViolation&) const = default;
};

struct DiffSummary {
  CompareProfile profile = CompareProfile::Lavapipe;
  uint32_t width = 0, height = 0, samples = 1;
  DepthFormat depth_format = DepthFormat::None;
  bool depth_compared = false;    // both renders carry depth
  uint64_t pixels = 0;            // width * height
  uint64_t samples_compared = 0;  // pixels * samples
  uint64_t missing = 0, unexpected = 0, wrong_owner = 0, allowed = 0;
  uint64_t allowed_owner = 0;  // spec profile: Must samples owned as an exact device may own them
  uint64_t covered_match = 0;  // covered by the same owner in both
  uint64_t bad_pixels = 0;     // pixels with at least one missing/unexpected/wrong-owner/depth sample
  DepthStats depth;
  // Spec profile with depth intervals: Must and May samples checked against them.
  bool depth_intervals_checked = false;
  uint64_t depth_outside = 0;
  DepthViolation worst_outside;
  std::vector<BadSample> first_bad;

  uint64_t coverage_mismatches() const { return missing + unexpected + wrong_owner; }
  bool operator==(const DiffSummary&) const = default;
};

struct SceneDiff {
  DiffSummary summary;
  std::vector<SampleClass> sample_class;  // per sample, RenderResult layout
  std::vector<float> depth_diff_r;        // per sample, |diff| in r (0 where not compared); empty unless depth_compared
};

// Throws std::invalid_argument when the two results differ in size, samples or depth format.
// A render without depth (while the other has it) leaves depth uncompared: depth_compared false.
SceneDiff diff_results(const RenderResult& expected, const RenderResult& actual, CompareProfile profile,
                       size_t max_bad_samples = kMaxBadSamples);

// The class of one sample (the same rule diff_results applies to every sample).
SampleClass classify_sample(const RenderResult& expected, const RenderResult& actual, CompareProfile profile,
                            size_t index);

// One line for a person: "match", "missing", "unexpected", "wrong owner",
// "depth off by 3 LSB (1.5 r)", "allowed (may): missing".
std::string describe_sample(const RenderResult& expected, const RenderResult& actual, CompareProfile profile,
                            uint32_t x, uint32_t y, uint32_t sample);

}  // namespace rastercmp
