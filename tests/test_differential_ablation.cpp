// The differential check can fail: the CPU lavapipe profile with one of lavapipe's rules replaced
// by a classic alternative must differ from the driver on scenes made to expose that rule.
//  - snap = round_half_away (util_iround instead of cvtps2dq's round-to-nearest-even) on vertices
//    at odd multiples of 1/512 px, where the two roundings disagree;
//  - tie_break = none (no top-left +1) on triangles with edges through pixel centres;
//  - the host FMA behaviour inverted: depth differs, coverage does not (docs/lavapipe-rules.md §7.1).
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_differential_scenes.hpp"

namespace rastercmp::differential {
namespace {

class Ablation : public ::testing::TestWithParam<uint32_t> {
 protected:
  void SetUp() override {
    const std::string reason = missing_vulkan_reason();
    if (!reason.empty()) GTEST_SKIP() << "no Vulkan device: " << reason;
  }

  static DiffFigures run(const Scene& scene, const CpuVariant& variant) {
    std::string report;
    const DiffFigures f = run_differential(scene, variant, report);
    fmt::print("{}: {} primitives, {} covered samples, {} coverage mismatches, {} depth mismatches\n", scene.name,
               f.primitives, f.covered_samples, f.coverage_mismatches, f.depth_mismatches);
    return f;
  }
};

TEST_P(Ablation, RoundHalfAwaySnappingDiffersFromLavapipe) {
  const Scene scene = grid_triangles(GetParam(), /*fine_grid_bits=*/9);
  EXPECT_EQ(run(scene, {}).coverage_mismatches, 0u) << "the exact path must match this scene";
  EXPECT_GT(run(scene, CpuVariant{{{"snap", "round_half_away"}}, false}).coverage_mismatches, 0u);
}

TEST_P(Ablation, NoTieBreakBiasDiffersFromLavapipe) {
  const Scene scene = grid_triangles(GetParam());
  EXPECT_EQ(run(scene, {}).coverage_mismatches, 0u) << "the exact path must match this scene";
  EXPECT_GT(run(scene, CpuVariant{{{"tie_break", "none"}}, false}).coverage_mismatches, 0u);
}

TEST_P(Ablation, InvertedFmaChangesDepthButNotCoverage) {
  const Scene scene = perspective_triangles(GetParam());
  const DiffFigures f = run(scene, CpuVariant{{}, true});
  EXPECT_EQ(f.coverage_mismatches, 0u);
  EXPECT_GT(f.depth_mismatches, 0u);
}

INSTANTIATE_TEST_SUITE_P(Seeds, Ablation, ::testing::Values(101u, 102u, 103u),
                         [](const ::testing::TestParamInfo<uint32_t>& param_info) {
                           return "seed" + std::to_string(param_info.param);
                         });

}  // namespace
}  // namespace rastercmp::differential
