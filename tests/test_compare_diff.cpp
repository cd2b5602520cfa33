// compare/diff + compare/verdict on planted differences: two synthetic RenderResults that differ
// in known samples must report exactly those samples, for owner and for depth, per format.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <stdexcept>

#include "compare/depth_units.hpp"
#include "compare/diff.hpp"
#include "compare/verdict.hpp"

namespace rastercmp {
namespace {

constexpr uint32_t kOwnerA = encode_owner(0, 7);
constexpr uint32_t kOwnerB = encode_owner(1, 2);

uint32_t raw_of(DepthFormat format, double depth) {
  switch (format) {
    case DepthFormat::D16Unorm: return uint32_t(depth * 65535.0 + 0.5);
    case DepthFormat::X8D24Unorm: return uint32_t(depth * 16777215.0 + 0.5);
    case DepthFormat::D32Sfloat: return std::bit_cast<uint32_t>(float(depth));
    case DepthFormat::None: break;
  }
  return 0;
}

// A w x h render whose left half is covered by kOwnerA at depth 0.5, the rest background at 1.0.
RenderResult half_covered(uint32_t w, uint32_t h, uint32_t samples, DepthFormat format) {
  RenderResult r;
  r.width = w;
  r.height = h;
  r.samples = samples;
  r.depth_format = format;
  r.owner.assign(size_t(w) * h * samples, kOwnerBackground);
  if (format != DepthFormat::None) r.depth_raw.assign(r.owner.size(), raw_of(format, 1.0));
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w / 2; ++x)
      for (uint32_t s = 0; s < samples; ++s) {
        r.owner[r.index(x, y, s)] = kOwnerA;
        if (r.has_depth()) r.depth_raw[r.index(x, y, s)] = raw_of(format, 0.5);
      }
  return r;
}

struct PlantCase {
  DepthFormat format;
  uint32_t samples;
};

class PlantedDifference : public ::testing::TestWithParam<PlantCase> {};

TEST_P(PlantedDifference, IdenticalRendersPassWithNothingCounted) {
  const auto [format, samples] = GetParam();
  const RenderResult r = half_covered(9, 7, samples, format);
  const SceneDiff d = diff_results(r, r, CompareProfile::Lavapipe);
  EXPECT_EQ(d.summary.coverage_mismatches(), 0u);
  EXPECT_EQ(d.summary.depth.mismatches, 0u);
  EXPECT_EQ(d.summary.bad_pixels, 0u);
  EXPECT_TRUE(d.summary.first_bad.empty());
  EXPECT_EQ(d.summary.covered_match, uint64_t(4) * 7 * samples);
  EXPECT_EQ(d.summary.pixels, 63u);
  EXPECT_EQ(decide_verdict(d.summary, 0).verdict, Verdict::Pass);
}

// Changes one sample's owner in `actual` and checks that exactly it is reported, with the class.
void expect_one_owner_difference(PlantCase p, uint32_t x, uint32_t y, uint32_t sample, uint32_t actual_owner,
                                 const char* kind) {
  const RenderResult expected = half_covered(9, 7, p.samples, p.format);
  RenderResult actual = expected;
  actual.owner[actual.index(x, y, sample)] = actual_owner;
  if (actual.has_depth()) actual.depth_raw[actual.index(x, y, sample)] = raw_of(p.format, 0.25);
  const SceneDiff d = diff_results(expected, actual, CompareProfile::Lavapipe);
  const DiffSummary& s = d.summary;
  EXPECT_EQ(s.coverage_mismatches(), 1u);
  EXPECT_EQ(s.missing, std::string(kind) == "missing" ? 1u : 0u);
  EXPECT_EQ(s.unexpected, std::string(kind) == "unexpected" ? 1u : 0u);
  EXPECT_EQ(s.wrong_owner, std::string(kind) == "wrong_owner" ? 1u : 0u);
  EXPECT_EQ(s.depth.mismatches, 0u) << "a coverage difference is not counted again as depth";
  EXPECT_EQ(s.bad_pixels, 1u);
  ASSERT_EQ(s.first_bad.size(), 1u);
  EXPECT_EQ(s.first_bad[0].at, (SampleLocation{x, y, sample}));
  EXPECT_EQ(s.first_bad[0].kind, kind);
  EXPECT_EQ(s.first_bad[0].expected_owner, expected.owner[expected.index(x, y, sample)]);
  EXPECT_EQ(s.first_bad[0].actual_owner, actual_owner);
  EXPECT_EQ(d.sample_class[expected.index(x, y, sample)], std::string(kind) == "missing" ? SampleClass::Missing
                                                          : std::string(kind) == "unexpected"
                                                              ? SampleClass::Unexpected
                                                              : SampleClass::WrongOwner);
  EXPECT_EQ(decide_verdict(s, 0).verdict, Verdict::Fail);
  // The message names the counts from the judged side: the diff's missing (the CPU render has the
  // sample, the device lacks it) is a sample a judged CPU method adds.
  const std::string device = decide_verdict(s, 0, Judged::Device).message;
  const std::string method = decide_verdict(s, 0, Judged::CpuMethod).message;
  if (std::string(kind) == "missing") {
    EXPECT_NE(device.find("1 missing, 0 unexpected"), std::string::npos) << device;
    EXPECT_NE(method.find("0 the method lacks, 1 the method adds"), std::string::npos) << method;
  } else if (std::string(kind) == "unexpected") {
    EXPECT_NE(device.find("0 missing, 1 unexpected"), std::string::npos) << device;
    EXPECT_NE(method.find("1 the method lacks, 0 the method adds"), std::string::npos) << method;
  }
}

TEST_P(PlantedDifference, MissingSampleIsReportedExactly) {
  const PlantCase p = GetParam();
  expect_one_owner_difference(p, 2, 5, p.samples - 1, kOwnerBackground, "missing");
}

TEST_P(PlantedDifference, UnexpectedSampleIsReportedExactly) {
  const PlantCase p = GetParam();
  expect_one_owner_difference(p, 8, 0, 0, kOwnerB, "unexpected");
}

TEST_P(PlantedDifference, WrongOwnerIsReportedExactly) {
  const PlantCase p = GetParam();
  expect_one_owner_difference(p, 0, 6, p.samples / 2, kOwnerB, "wrong_owner");
}

class PlantedDepthDifference : public ::testing::TestWithParam<PlantCase> {};

TEST_P(PlantedDepthDifference, IsReportedExactlyInFormatUnits) {
  const auto [format, samples] = GetParam();
  const RenderResult expected = half_covered(9, 7, samples, format);
  RenderResult actual = expected;
  const size_t i = actual.index(3, 4, samples - 1);
  actual.depth_raw[i] += 3;  // 3 LSB (UNORM) or 3 ULP (float, 0.5 + 3 ULP stays in its binade)
  const SceneDiff d = diff_results(expected, actual, CompareProfile::Lavapipe);
  const DiffSummary& s = d.summary;
  EXPECT_EQ(s.coverage_mismatches(), 0u);
  EXPECT_EQ(s.depth.mismatches, 1u);
  EXPECT_EQ(s.depth.max_raw, 3u);
  EXPECT_EQ(s.depth.p50_raw, 3u);
  EXPECT_EQ(s.depth.p95_raw, 3u);
  EXPECT_EQ(s.depth.max_at, (SampleLocation{3, 4, samples - 1}));
  EXPECT_EQ(s.depth.max_expected_raw, expected.depth_raw[i]);
  EXPECT_EQ(s.depth.max_actual_raw, actual.depth_raw[i]);
  // r = 2 LSB for UNORM (lavapipe's 2/(2^n-1)); for D32 at 0.5, r = 2^(-1-23) = 1 ULP.
  EXPECT_DOUBLE_EQ(s.depth.max_r, format == DepthFormat::D32Sfloat ? 3.0 : 1.5);
  ASSERT_EQ(s.first_bad.size(), 1u);
  EXPECT_EQ(s.first_bad[0].kind, "depth");
  EXPECT_EQ(s.first_bad[0].depth_diff_raw, 3u);
  EXPECT_FLOAT_EQ(d.depth_diff_r[i], float(s.depth.max_r));
  EXPECT_EQ(decide_verdict(s, 0).verdict, Verdict::Fail);
}

const auto kDepthCases = ::testing::Values(PlantCase{DepthFormat::D16Unorm, 1}, PlantCase{DepthFormat::X8D24Unorm, 1},
                                           PlantCase{DepthFormat::D32Sfloat, 1}, PlantCase{DepthFormat::D16Unorm, 4},
                                           PlantCase{DepthFormat::X8D24Unorm, 4}, PlantCase{DepthFormat::D32Sfloat, 4});
INSTANTIATE_TEST_SUITE_P(Formats, PlantedDepthDifference, kDepthCases);
INSTANTIATE_TEST_SUITE_P(Formats, PlantedDifference,
                         ::testing::Values(PlantCase{DepthFormat::None, 1}, PlantCase{DepthFormat::D16Unorm, 1},
                                           PlantCase{DepthFormat::X8D24Unorm, 1}, PlantCase{DepthFormat::D32Sfloat, 1},
                                           PlantCase{DepthFormat::None, 4}, PlantCase{DepthFormat::D16Unorm, 4},
                                           PlantCase{DepthFormat::X8D24Unorm, 4},
                                           PlantCase{DepthFormat::D32Sfloat, 4}));

TEST(DepthUnits, UnormCountsLsbAndHalvesForR) {
  EXPECT_EQ(depth_diff_raw_units(DepthFormat::D16Unorm, 0x10, 0x13), 3u);
  EXPECT_DOUBLE_EQ(depth_diff_r_units(DepthFormat::D16Unorm, 0x10, 0x13), 1.5);
  // The X8 padding bits of X8_D24 carry no depth.
  EXPECT_EQ(depth_diff_raw_units(DepthFormat::X8D24Unorm, 0xAB000005, 0x00000005), 0u);
  EXPECT_DOUBLE_EQ(depth_bias_r(DepthFormat::D16Unorm, 0, 0), 2.0 / 65535.0);
  EXPECT_DOUBLE_EQ(depth_bias_r(DepthFormat::X8D24Unorm, 0, 0), 2.0 / 16777215.0);
}

TEST(DepthUnits, FloatCountsUlpAcrossBinadesAndRAtTheLargerDepth) {
  const uint32_t half = std::bit_cast<uint32_t>(0.5f);
  EXPECT_EQ(depth_diff_raw_units(DepthFormat::D32Sfloat, half - 1, half), 1u);   // just below 0.5 → 0.5
  EXPECT_EQ(depth_diff_raw_units(DepthFormat::D32Sfloat, 0x80000000u, 0u), 0u);  // -0 and +0
  EXPECT_EQ(depth_diff_raw_units(DepthFormat::D32Sfloat, std::bit_cast<uint32_t>(-0.0f),
                                 std::bit_cast<uint32_t>(std::nextafter(0.0f, 1.0f))),
            1u);
  // r at 0.5 is 2^(-1-23); the ULP just below 0.5 is 2^-25, half of it.
  EXPECT_DOUBLE_EQ(depth_bias_r(DepthFormat::D32Sfloat, half - 1, half), std::ldexp(1.0, -24));
  EXPECT_DOUBLE_EQ(depth_diff_r_units(DepthFormat::D32Sfloat, half - 1, half), 0.5);
  EXPECT_DOUBLE_EQ(
      depth_diff_r_units(DepthFormat::D32Sfloat, std::bit_cast<uint32_t>(1.0f), std::bit_cast<uint32_t>(0.75f)),
      0.25 / std::ldexp(1.0, -23));
}

TEST(DiffStats, PercentilesAreNearestRankOverTheDifferingSamples) {
  RenderResult expected = half_covered(10, 10, 1, DepthFormat::X8D24Unorm);
  RenderResult actual = expected;
  for (uint32_t k = 1; k <= 100; ++k) actual.depth_raw[k - 1] -= k;  // sample k-1 off by k LSB
  const DepthStats d = diff_results(expected, actual, CompareProfile::Lavapipe).summary.depth;
  EXPECT_EQ(d.mismatches, 100u);
  EXPECT_EQ(d.p50_raw, 50u);
  EXPECT_EQ(d.p95_raw, 95u);
  EXPECT_EQ(d.max_raw, 100u);
  EXPECT_DOUBLE_EQ(d.p95_r, 47.5);
  EXPECT_EQ(d.max_at, (SampleLocation{9, 9, 0}));
}

TEST(DiffStats, FirstBadSamplesAreKeptInScanOrderUpToTheLimit) {
  const RenderResult expected = half_covered(8, 8, 1, DepthFormat::None);
  RenderResult actual = expected;
  for (uint32_t y = 0; y < 8; ++y) actual.owner[actual.index(7, y)] = kOwnerB;  // 8 unexpected
  const DiffSummary s = diff_results(expected, actual, CompareProfile::Lavapipe, 3).summary;
  EXPECT_EQ(s.unexpected, 8u);
  ASSERT_EQ(s.first_bad.size(), 3u);
  for (uint32_t k = 0; k < 3; ++k) EXPECT_EQ(s.first_bad[k].at, (SampleLocation{7, k, 0}));
}

TEST(DiffStats, RendersOfDifferentShapesAreRejected) {
  const RenderResult a = half_covered(8, 8, 1, DepthFormat::D16Unorm);
  EXPECT_THROW(diff_results(a, half_covered(8, 9, 1, DepthFormat::D16Unorm), CompareProfile::Lavapipe),
               std::invalid_argument);
  EXPECT_THROW(diff_results(a, half_covered(8, 8, 4, DepthFormat::D16Unorm), CompareProfile::Lavapipe),
               std::invalid_argument);
  EXPECT_THROW(diff_results(a, half_covered(8, 8, 1, DepthFormat::D32Sfloat), CompareProfile::Lavapipe),
               std::invalid_argument);
}

TEST(DiffStats, DepthIsLeftUncomparedWhenOneRenderHasNone) {
  const RenderResult expected = half_covered(6, 6, 4, DepthFormat::D32Sfloat);
  RenderResult actual = expected;
  actual.depth_raw.clear();  // e.g. a device that cannot sample multisampled depth
  actual.owner[actual.index(1, 1, 2)] = kOwnerBackground;
  const SceneDiff d = diff_results(expected, actual, CompareProfile::Lavapipe);
  EXPECT_FALSE(d.summary.depth_compared);
  EXPECT_TRUE(d.depth_diff_r.empty());
  EXPECT_EQ(d.summary.missing, 1u);
  EXPECT_EQ(d.summary.depth.mismatches, 0u);
  ASSERT_EQ(d.summary.first_bad.size(), 1u);
  EXPECT_FALSE(d.summary.first_bad[0].has_depth);
  const VerdictDecision v = decide_verdict(d.summary, 0);
  EXPECT_EQ(v.verdict, Verdict::Fail);
  EXPECT_NE(v.message.find("depth not compared"), std::string::npos) << v.message;
  EXPECT_TRUE(diff_results(expected, expected, CompareProfile::Lavapipe).summary.depth_compared);
}

// Spec profile: class map Must on the covered half, May on column 4 (the edge), MustNot beyond.
RenderResult with_classes(RenderResult r) {
  r.coverage_class.assign(r.owner.size(), CoverageClass::MustNot);
  for (uint32_t y = 0; y < r.height; ++y)
    for (uint32_t x = 0; x < r.width; ++x)
      for (uint32_t s = 0; s < r.samples; ++s)
        r.coverage_class[r.index(x, y, s)] = x < r.width / 2 - 1 ? CoverageClass::Must
                                             : x <= r.width / 2  ? CoverageClass::May
                                                                 : CoverageClass::MustNot;
  return r;
}

TEST(SpecProfile, MaySamplesNeverFail) {
  const RenderResult expected = with_classes(half_covered(10, 4, 4, DepthFormat::D16Unorm));
  RenderResult actual = expected;
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t s = 0; s < 4; ++s) {
      actual.owner[actual.index(4, y, s)] = kOwnerBackground;  // may: left out
      actual.owner[actual.index(5, y, s)] = kOwnerB;           // may: drawn by another primitive
    }
  const SceneDiff d = diff_results(expected, actual, CompareProfile::Spec);
  EXPECT_EQ(d.summary.allowed, 32u);
  EXPECT_EQ(d.summary.coverage_mismatches(), 0u);
  EXPECT_TRUE(d.summary.first_bad.empty());
  EXPECT_EQ(decide_verdict(d.summary, 2).verdict, Verdict::Pass);
  // The same renders fail the exact profile.
  EXPECT_EQ(decide_verdict(diff_results(expected, actual, CompareProfile::Lavapipe).summary, 2).verdict, Verdict::Fail);
}

TEST(SpecProfile, MustAndMustNotViolationsFail) {
  const RenderResult expected = with_classes(half_covered(10, 4, 1, DepthFormat::None));
  RenderResult missing = expected;
  missing.owner[missing.index(1, 1)] = kOwnerBackground;
  const DiffSummary m = diff_results(expected, missing, CompareProfile::Spec).summary;
  EXPECT_EQ(m.missing, 1u);
  EXPECT_EQ(decide_verdict(m, 2).verdict, Verdict::Fail);
  RenderResult unexpected = expected;
  unexpected.owner[unexpected.index(8, 2)] = kOwnerA;
  const DiffSummary u = diff_results(expected, unexpected, CompareProfile::Spec).summary;
  EXPECT_EQ(u.unexpected, 1u);
  EXPECT_EQ(decide_verdict(u, 2).verdict, Verdict::Fail);
}

TEST(SpecProfile, WrongOwnerOrDepthBeyondToleranceIsAQualityWarning) {
  const RenderResult expected = with_classes(half_covered(10, 4, 1, DepthFormat::D16Unorm));
  RenderResult owner = expected;
  owner.owner[owner.index(0, 0)] = kOwnerB;
  EXPECT_EQ(decide_verdict(diff_results(expected, owner, CompareProfile::Spec).summary, 2).verdict,
            Verdict::QualityWarning);
  RenderResult depth = expected;
  depth.depth_raw[depth.index(0, 0)] += 4;  // 2 r: within a 2 r tolerance
  EXPECT_EQ(decide_verdict(diff_results(expected, depth, CompareProfile::Spec).summary, 2).verdict, Verdict::Pass);
  depth.depth_raw[depth.index(0, 0)] += 1;  // 2.5 r
  EXPECT_EQ(decide_verdict(diff_results(expected, depth, CompareProfile::Spec).summary, 2).verdict,
            Verdict::QualityWarning);
}

// With depth intervals, a Must or May sample's stored depth is judged by its interval alone: the
// bound itself passes, one step past it fails and the message names the bound and its term; a
// wrong owner whose depth is inside stays a QualityWarning; MustNot samples are not checked.
TEST(SpecProfile, DepthOutsideItsIntervalFailsInsidePasses) {
  for (const DepthFormat format : {DepthFormat::D16Unorm, DepthFormat::D32Sfloat}) {
    RenderResult expected = with_classes(half_covered(10, 4, 1, format));
    const uint32_t lo = raw_of(format, 0.25), hi = raw_of(format, 0.75), clear = raw_of(format, 1.0);
    expected.depth_interval.assign(expected.owner.size(),
                                   DepthInterval{lo, hi, DepthTerm::Snapping, DepthTerm::Bias, false});
    for (uint32_t y = 0; y < 4; ++y)  // the May column 5 is background, MustNot is never checked
      for (uint32_t x = 5; x < 10; ++x) expected.depth_interval[expected.index(x, y)] = DepthInterval{lo, clear};
    RenderResult actual = expected;
    actual.depth_raw[actual.index(0, 0)] = hi;  // on the bounds: inside
    actual.depth_raw[actual.index(1, 0)] = lo;
    actual.depth_raw[actual.index(9, 3)] = lo;  // MustNot sample: not checked
    DiffSummary d = diff_results(expected, actual, CompareProfile::Spec).summary;
    EXPECT_TRUE(d.depth_intervals_checked);
    EXPECT_EQ(d.depth_outside, 0u) << to_string(format);
    EXPECT_EQ(decide_verdict(d, 2).verdict, Verdict::Pass) << decide_verdict(d, 2).message;
    actual.depth_raw[actual.index(0, 0)] = hi + 1;  // one LSB / ULP above hi
    d = diff_results(expected, actual, CompareProfile::Spec).summary;
    EXPECT_EQ(d.depth_outside, 1u);
    EXPECT_EQ(d.worst_outside.at, (SampleLocation{0, 0, 0}));
    EXPECT_TRUE(d.worst_outside.above);
    EXPECT_EQ(d.worst_outside.distance, 1u);
    VerdictDecision v = decide_verdict(d, 2);
    EXPECT_EQ(v.verdict, Verdict::Fail);
    EXPECT_NE(v.message.find("above hi"), std::string::npos) << v.message;
    EXPECT_NE(v.message.find("depth bias"), std::string::npos) << v.message;
    ASSERT_FALSE(d.first_bad.empty());
    EXPECT_EQ(d.first_bad[0].kind, "depth_outside");
    actual.depth_raw[actual.index(0, 0)] = hi;
    actual.depth_raw[actual.index(4, 2)] = lo - 1;  // a May sample, one below lo
    d = diff_results(expected, actual, CompareProfile::Spec).summary;
    EXPECT_EQ(d.depth_outside, 1u);
    v = decide_verdict(d, 2);
    EXPECT_NE(v.message.find("below lo"), std::string::npos) << v.message;
    EXPECT_NE(v.message.find("vertex snapping"), std::string::npos) << v.message;
    actual.depth_raw[actual.index(4, 2)] = lo;
    actual.owner[actual.index(2, 2)] = kOwnerB;  // another primitive won, its depth inside
    v = decide_verdict(diff_results(expected, actual, CompareProfile::Spec).summary, 2);
    EXPECT_EQ(v.verdict, Verdict::QualityWarning);
    EXPECT_NE(v.message.find("only arithmetic precision decides which primitive wins"), std::string::npos)
        << v.message;
    EXPECT_NE(v.message.find("leaves to quality"), std::string::npos) << v.message;
  }
}

// RenderResult::owner_alternatives (docs/spec-profile.md "Owners"): a Must sample owned by a
// primitive that a device computing exactly leaves there is an allowed owner and the scene passes;
// any other owner stays a wrong owner (QualityWarning), a listed owner does not excuse a missing
// sample, and the alternatives of one sample say nothing of its neighbours.
TEST(SpecProfile, OwnerAlternativesAllowThatOwnerOnlyThere) {
  RenderResult expected = with_classes(half_covered(10, 4, 1, DepthFormat::None));
  const size_t listed = expected.index(2, 1);
  expected.owner_alternatives = {{uint64_t(listed), kOwnerB}};
  RenderResult actual = expected;
  actual.owner[listed] = kOwnerB;
  SceneDiff d = diff_results(expected, actual, CompareProfile::Spec);
  EXPECT_EQ(d.summary.allowed_owner, 1u);
  EXPECT_EQ(d.summary.wrong_owner, 0u);
  EXPECT_EQ(d.summary.coverage_mismatches(), 0u);
  EXPECT_EQ(d.sample_class[listed], SampleClass::AllowedOwner);
  EXPECT_TRUE(d.summary.first_bad.empty());
  VerdictDecision v = decide_verdict(d.summary, 2);
  EXPECT_EQ(v.verdict, Verdict::Pass) << v.message;
  EXPECT_NE(v.message.find("1 allowed owner"), std::string::npos) << v.message;
  EXPECT_EQ(describe_sample(expected, actual, CompareProfile::Spec, 2, 1, 0).rfind("allowed owner", 0), 0u);
  // Another owner there, or the listed owner one pixel over: wrong owners.
  actual.owner[listed] = kOwnerA + 7;
  d = diff_results(expected, actual, CompareProfile::Spec);
  EXPECT_EQ(d.summary.wrong_owner, 1u);
  EXPECT_EQ(decide_verdict(d.summary, 2).verdict, Verdict::QualityWarning);
  actual.owner[listed] = kOwnerA;
  actual.owner[expected.index(3, 1)] = kOwnerB;
  d = diff_results(expected, actual, CompareProfile::Spec);
  EXPECT_EQ(d.summary.wrong_owner, 1u);
  EXPECT_EQ(d.summary.allowed_owner, 0u);
  // Covered by neither: missing, whatever the alternatives.
  actual.owner[expected.index(3, 1)] = kOwnerA;
  actual.owner[listed] = kOwnerBackground;
  d = diff_results(expected, actual, CompareProfile::Spec);
  EXPECT_EQ(d.summary.missing, 1u);
  EXPECT_EQ(decide_verdict(d.summary, 2).verdict, Verdict::Fail);
  // The lavapipe profile is bit-exact: the alternatives do not count there.
  actual.owner[listed] = kOwnerB;
  EXPECT_EQ(diff_results(expected, actual, CompareProfile::Lavapipe).summary.wrong_owner, 1u);
  // Alternatives past the render's samples are a malformed render.
  expected.owner_alternatives = {{uint64_t(expected.owner.size()), kOwnerB}};
  EXPECT_THROW(diff_results(expected, actual, CompareProfile::Spec), std::invalid_argument);
}

TEST(SpecProfile, ToleranceGrowsWithTheUnormBiasConstant) {
  Scene scene;
  scene.depth_format = DepthFormat::D16Unorm;
  Draw draw;
  draw.state.depth_bias = DepthBias{true, -8.0f, 1.0f, 0.0f};
  scene.draws.push_back(draw);
  EXPECT_DOUBLE_EQ(spec_depth_tolerance_r(scene), 2.0 + 4.0);
  scene.depth_format = DepthFormat::D32Sfloat;
  EXPECT_DOUBLE_EQ(spec_depth_tolerance_r(scene), 2.0);
}

TEST(Describe, OneLinePerClass) {
  const RenderResult expected = with_classes(half_covered(10, 4, 1, DepthFormat::D16Unorm));
  RenderResult actual = expected;
  actual.owner[actual.index(0, 0)] = kOwnerBackground;
  actual.owner[actual.index(9, 0)] = kOwnerA;
  actual.owner[actual.index(1, 0)] = kOwnerB;
  actual.depth_raw[actual.index(2, 0)] += 6;
  actual.owner[actual.index(4, 0)] = kOwnerBackground;
  const auto lavapipe = CompareProfile::Lavapipe;
  EXPECT_EQ(describe_sample(expected, actual, lavapipe, 0, 0, 0), "missing");
  EXPECT_EQ(describe_sample(expected, actual, lavapipe, 9, 0, 0), "unexpected");
  EXPECT_EQ(describe_sample(expected, actual, lavapipe, 1, 0, 0), "wrong owner");
  EXPECT_EQ(describe_sample(expected, actual, lavapipe, 2, 0, 0), "depth off by 6 LSB (3 r)");
  EXPECT_EQ(describe_sample(expected, actual, lavapipe, 3, 0, 0), "match");
  EXPECT_EQ(describe_sample(expected, actual, CompareProfile::Spec, 4, 0, 0), "allowed (may): missing");
  EXPECT_THROW(describe_sample(expected, actual, lavapipe, 10, 0, 0), std::invalid_argument);
}

// Any set of planted owner changes is reported exactly: the counts, and the first bad samples
// are the planted ones in scan order.
RC_GTEST_PROP(PlantedDifferenceProperty, ExactlyThePlantedSamplesAreReported, ()) {
  const uint32_t w = *rc::gen::inRange<uint32_t>(1, 12);
  const uint32_t h = *rc::gen::inRange<uint32_t>(1, 12);
  const uint32_t samples = *rc::gen::element<uint32_t>(1, 4);
  const RenderResult expected = half_covered(w, h, samples, DepthFormat::D32Sfloat);
  RenderResult actual = expected;
  const auto flips = *rc::gen::container<std::vector<bool>>(expected.owner.size(), rc::gen::arbitrary<bool>());
  uint64_t planted = 0;
  std::vector<SampleLocation> planted_at;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (uint32_t s = 0; s < samples; ++s)
        if (flips[expected.index(x, y, s)]) {
          uint32_t& owner = actual.owner[expected.index(x, y, s)];
          owner = owner == kOwnerBackground ? kOwnerB : kOwnerBackground;
          ++planted;
          planted_at.push_back({x, y, s});
        }
  const DiffSummary d = diff_results(expected, actual, CompareProfile::Lavapipe).summary;
  RC_ASSERT(d.coverage_mismatches() == planted);
  RC_ASSERT(d.depth.mismatches == 0u);
  RC_ASSERT(d.first_bad.size() == std::min<size_t>(planted, kMaxBadSamples));
  for (size_t k = 0; k < d.first_bad.size(); ++k) RC_ASSERT(d.first_bad[k].at == planted_at[k]);
}

}  // namespace
}  // namespace rastercmp
