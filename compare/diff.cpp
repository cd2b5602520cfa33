#include "compare/diff.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "compare/depth_units.hpp"

namespace rastercmp {
namespace {

// The spec profile's class of a sample; without a class map, the expected coverage decides.
CoverageClass coverage_class_at(const RenderResult& expected, size_t index) {
  if (!expected.coverage_class.empty()) return expected.coverage_class[index];
  return expected.owner[index] == kOwnerBackground ? CoverageClass::MustNot : CoverageClass::Must;
}

// The coverage difference a sample would have under exact comparison.
SampleClass exact_class(uint32_t expected_owner, uint32_t actual_owner) {
  const bool expected_covered = expected_owner != kOwnerBackground;
  const bool actual_covered = actual_owner != kOwnerBackground;
  if (expected_owner == actual_owner) return expected_covered ? SampleClass::Correct : SampleClass::Background;
  if (!actual_covered) return SampleClass::Missing;
  if (!expected_covered) return SampleClass::Unexpected;
  return SampleClass::WrongOwner;
}

// tcuRasterizationVerifier: FULL must be covered, NONE must not, PARTIAL is "anything goes". A
// Must sample owned by another primitive is an allowed owner when an exact device may own it so.
SampleClass spec_class(const RenderResult& expected, size_t index, uint32_t actual_owner) {
  const uint32_t expected_owner = expected.owner[index];
  const bool actual_covered = actual_owner != kOwnerBackground;
  switch (coverage_class_at(expected, index)) {
    case CoverageClass::May:
      return expected_owner == actual_owner ? exact_class(expected_owner, actual_owner) : SampleClass::Allowed;
    case CoverageClass::Must:
      if (!actual_covered) return SampleClass::Missing;
      if (expected_owner != kOwnerBackground && expected_owner != actual_owner)
        return is_owner_alternative(expected, index, actual_owner) ? SampleClass::AllowedOwner
                                                                   : SampleClass::WrongOwner;
      return SampleClass::Correct;
    case CoverageClass::MustNot: return actual_covered ? SampleClass::Unexpected : SampleClass::Background;
  }
  return SampleClass::Background;
}

void check_comparable(const RenderResult& expected, const RenderResult& actual) {
  if (expected.width != actual.width || expected.height != actual.height || expected.samples != actual.samples)
    throw std::invalid_argument(fmt::format("the renders differ in size: expected {}x{}x{}, actual {}x{}x{}",
                                            expected.width, expected.height, expected.samples, actual.width,
                                            actual.height, actual.samples));
  if (expected.depth_format != actual.depth_format)
    throw std::invalid_argument(fmt::format("the renders differ in depth: expected {}, actual {}",
                                            to_string(expected.depth_format), to_string(actual.depth_format)));
  const size_t n = size_t(expected.width) * expected.height * expected.samples;
  if (expected.owner.size() != n || actual.owner.size() != n ||
      (expected.has_depth() && expected.depth_raw.size() != n) ||
      (actual.has_depth() && actual.depth_raw.size() != n) ||
      (!expected.coverage_class.empty() && expected.coverage_class.size() != n) ||
      (!expected.depth_interval.empty() && expected.depth_interval.size() != n) ||
      (!expected.owner_alternatives.empty() && expected.owner_alternatives.back().sample >= n))
    throw std::invalid_argument("a render's arrays do not match its width * height * samples");
}

// Nearest-rank percentile of an unsorted list (reorders it).
template <typename T>
T percentile(std::vector<T>& values, unsigned percent) {
  if (values.empty()) return T{};
  const size_t rank = (size_t(percent) * values.size() + 99) / 100;  // ceil(p * n)
  const size_t index = rank == 0 ? 0 : rank - 1;
  std::nth_element(values.begin(), values.begin() + index, values.end());
  return values[index];
}

// The spec interval check of one sample: true when its stored depth is outside.
bool check_interval(const RenderResult& expected, const RenderResult& actual, size_t i, SampleLocation at,
                    DiffSummary& s) {
  const CoverageClass cls = coverage_class_at(expected, i);
  if (cls == CoverageClass::MustNot) return false;
  const DepthInterval& interval = expected.depth_interval[i];
  const uint32_t raw = actual.depth_raw[i];
  if (depth_in_interval(s.depth_format, interval, raw)) return false;
  ++s.depth_outside;
  const int64_t key = depth_raw_order(s.depth_format, raw);
  const bool above = key > depth_raw_order(s.depth_format, interval.hi_raw);
  const uint32_t bound = above ? interval.hi_raw : interval.lo_raw;
  const uint64_t distance = uint64_t(std::llabs(key - depth_raw_order(s.depth_format, bound)));
  if (s.depth_outside == 1 || distance > s.worst_outside.distance)
    s.worst_outside = {at, raw, bound, above, above ? interval.hi_term : interval.lo_term, distance};
  return true;
}

const char* bad_kind(SampleClass c) {
  switch (c) {
    case SampleClass::Missing: return "missing";
    case SampleClass::Unexpected: return "unexpected";
    case SampleClass::WrongOwner: return "wrong_owner";
    default: return "depth";
  }
}

bool is_coverage_error(SampleClass c) {
  return c == SampleClass::Missing || c == SampleClass::Unexpected || c == SampleClass::WrongOwner;
}

struct DepthAccumulator {
  std::vector<uint64_t> raw;
  std::vector<double> r;
};

void count_class(DiffSummary& s, SampleClass c) {
  switch (c) {
    case SampleClass::Missing: ++s.missing; break;
    case SampleClass::Unexpected: ++s.unexpected; break;
    case SampleClass::WrongOwner: ++s.wrong_owner; break;
    case SampleClass::Allowed: ++s.allowed; break;
    case SampleClass::AllowedOwner: ++s.allowed_owner; break;
    case SampleClass::Correct: ++s.covered_match; break;
    case SampleClass::Background: break;
  }
}

void finish_depth_stats(DepthStats& d, DepthAccumulator& acc) {
  d.mismatches = acc.raw.size();
  if (acc.raw.empty()) return;
  d.max_r = *std::max_element(acc.r.begin(), acc.r.end());
  d.p50_raw = percentile(acc.raw, 50);
  d.p95_raw = percentile(acc.raw, 95);
  d.p50_r = percentile(acc.r, 50);
  d.p95_r = percentile(acc.r, 95);
}

}  // namespace

const char* to_string(CompareProfile profile) { return profile == CompareProfile::Spec ? "spec" : "lavapipe"; }

const char* to_string(SampleClass c) {
  switch (c) {
    case SampleClass::Background: return "background";
    case SampleClass::Correct: return "correct";
    case SampleClass::Missing: return "missing";
    case SampleClass::Unexpected: return "unexpected";
    case SampleClass::WrongOwner: return "wrong owner";
    case SampleClass::Allowed: return "allowed";
    case SampleClass::AllowedOwner: return "allowed owner";
  }
  return "?";
}

SampleClass classify_sample(const RenderResult& expected, const RenderResult& actual, CompareProfile profile,
                            size_t index) {
  const uint32_t expected_owner = expected.owner[index], actual_owner = actual.owner[index];
  if (profile == CompareProfile::Lavapipe) return exact_class(expected_owner, actual_owner);
  return spec_class(expected, index, actual_owner);
}

SceneDiff diff_results(const RenderResult& expected, const RenderResult& actual, CompareProfile profile,
                       size_t max_bad_samples) {
  check_comparable(expected, actual);
  SceneDiff diff;
  DiffSummary& s = diff.summary;
  s.profile = profile;
  s.width = expected.width;
  s.height = expected.height;
  s.samples = expected.samples;
  s.depth_format = expected.depth_format;
  s.depth_compared = expected.has_depth() && actual.has_depth();
  s.pixels = uint64_t(s.width) * s.height;
  s.samples_compared = s.pixels * s.samples;
  diff.sample_class.resize(size_t(s.samples_compared));
  if (s.depth_compared) diff.depth_diff_r.assign(size_t(s.samples_compared), 0.0f);
  s.depth_intervals_checked =
      profile == CompareProfile::Spec && s.depth_compared && expected.depth_interval.size() == s.samples_compared;

  DepthAccumulator acc;
  for (uint32_t y = 0; y < s.height; ++y) {
    for (uint32_t x = 0; x < s.width; ++x) {
      bool pixel_bad = false;
      for (uint32_t sample = 0; sample < s.samples; ++sample) {
        const size_t i = expected.index(x, y, sample);
        const SampleClass c = classify_sample(expected, actual, profile, i);
        diff.sample_class[i] = c;
        count_class(s, c);
        BadSample bad{{x, y, sample}, bad_kind(c), expected.owner[i], actual.owner[i]};
        if (s.depth_compared) {
          bad.has_depth = true;
          bad.expected_depth_raw = expected.depth_raw[i];
          bad.actual_depth_raw = actual.depth_raw[i];
        }
        const bool coverage_agrees =
            expected.owner[i] == actual.owner[i] && (c == SampleClass::Correct || c == SampleClass::Background);
        if (coverage_agrees && s.depth_compared) {
          bad.depth_diff_raw = depth_diff_raw_units(s.depth_format, bad.expected_depth_raw, bad.actual_depth_raw);
          if (bad.depth_diff_raw != 0) {
            bad.depth_diff_r = depth_diff_r_units(s.depth_format, bad.expected_depth_raw, bad.actual_depth_raw);
            diff.depth_diff_r[i] = float(bad.depth_diff_r);
            if (bad.depth_diff_raw > s.depth.max_raw) {  // strict: the first in scan order wins ties
              s.depth.max_raw = bad.depth_diff_raw;
              s.depth.max_at = bad.at;
              s.depth.max_expected_raw = bad.expected_depth_raw;
              s.depth.max_actual_raw = bad.actual_depth_raw;
            }
            acc.raw.push_back(bad.depth_diff_raw);
            acc.r.push_back(bad.depth_diff_r);
          }
        }
        // A missing sample's depth is the clear value: counted once, as coverage.
        const bool coverage_fails = c == SampleClass::Missing || c == SampleClass::Unexpected;
        if (s.depth_intervals_checked && !coverage_fails && check_interval(expected, actual, i, bad.at, s) &&
            c != SampleClass::WrongOwner)
          bad.kind = "depth_outside";
        const bool sample_bad = is_coverage_error(c) || bad.depth_diff_raw != 0 || bad.kind == "depth_outside";
        pixel_bad = pixel_bad || sample_bad;
        if (sample_bad && s.first_bad.size() < max_bad_samples) s.first_bad.push_back(bad);
      }
      if (pixel_bad) ++s.bad_pixels;
    }
  }
  finish_depth_stats(s.depth, acc);
  return diff;
}

std::string describe_sample(const RenderResult& expected, const RenderResult& actual, CompareProfile profile,
                            uint32_t x, uint32_t y, uint32_t sample) {
  check_comparable(expected, actual);
  if (x >= expected.width || y >= expected.height || sample >= expected.samples)
    throw std::invalid_argument(fmt::format("sample ({}, {}) #{} is outside the {}x{}x{} render", x, y, sample,
                                            expected.width, expected.height, expected.samples));
  const size_t i = expected.index(x, y, sample);
  const SampleClass c = classify_sample(expected, actual, profile, i);
  if (c == SampleClass::Allowed)
    return fmt::format("allowed (may): {}", to_string(exact_class(expected.owner[i], actual.owner[i])));
  if (c == SampleClass::AllowedOwner) return "allowed owner: another primitive, as a device computing exactly may leave it";
  if (is_coverage_error(c)) return to_string(c);
  if (expected.has_depth() && actual.has_depth() && expected.owner[i] == actual.owner[i]) {
    const DepthFormat f = expected.depth_format;
    const uint64_t raw = depth_diff_raw_units(f, expected.depth_raw[i], actual.depth_raw[i]);
    if (raw != 0)
      return fmt::format("depth off by {} {} ({:.6g} r)", raw, depth_unit_name(f),
                         depth_diff_r_units(f, expected.depth_raw[i], actual.depth_raw[i]));
  }
  return "match";
}

}  // namespace rastercmp
