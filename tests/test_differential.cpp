// The CPU lavapipe profile against lavapipe itself, sample by sample: every owner id and every raw
// depth value must be equal (docs/lavapipe-rules.md "Tolerances": 0 and 0). Seeded random scenes,
// the seed in each test's name. Validation layer on, zero messages. Skips only without a device.
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_differential_scenes.hpp"

namespace rastercmp::differential {
namespace {

// Figures over the whole binary, printed at the end.
DiffFigures& totals() {
  static DiffFigures figures;
  return figures;
}

class TotalsPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    const DiffFigures& t = totals();
    if (t.scenes == 0) return;
    fmt::print(
        "differential totals: {} scenes, {} primitives, {} covered samples, {} coverage mismatches, {} depth "
        "mismatches\n",
        t.scenes, t.primitives, t.covered_samples, t.coverage_mismatches, t.depth_mismatches);
  }
};
const auto* const kTotalsPrinter = ::testing::AddGlobalTestEnvironment(new TotalsPrinter);

using SceneMaker = Scene (*)(uint32_t seed);

struct Family {
  const char* name;
  SceneMaker make;
};

class Differential : public ::testing::TestWithParam<std::tuple<Family, uint32_t>> {
 protected:
  void SetUp() override {
    const std::string reason = missing_vulkan_reason();
    if (!reason.empty()) GTEST_SKIP() << "no Vulkan device: " << reason;
  }
};

TEST_P(Differential, MatchesLavapipeExactly) {
  const auto& [family, seed] = GetParam();
  const Scene scene = family.make(seed);
  std::string report;
  const DiffFigures f = run_differential(scene, CpuVariant{}, report);
  totals().add(f);
  RecordProperty("primitives", int(f.primitives));
  RecordProperty("covered_samples", int(f.covered_samples));
  EXPECT_GT(f.covered_samples, 0u) << scene.name << " covers nothing: the scene tests nothing";
  EXPECT_EQ(f.coverage_mismatches, 0u) << scene.name << ": first differences\n" << report;
  EXPECT_EQ(f.depth_mismatches, 0u) << scene.name << ": first differences\n" << report;
}

// Deterministic corner cases of the draw region (docs/lavapipe-rules.md §2.5): an empty scissor, a scissor
// entirely outside the framebuffer, a viewport entirely outside it, over triangles covering the
// whole framebuffer.
class DifferentialRegion : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string reason = missing_vulkan_reason();
    if (!reason.empty()) GTEST_SKIP() << "no Vulkan device: " << reason;
  }

  static void expect_match(const char* name, std::optional<Rect2D> scissor, std::optional<Viewport> viewport,
                           uint32_t samples = 1) {
    Scene scene = make_scene(fmt::format("rastercmp.differential.region.{}", name), 32, 16, DepthFormat::X8D24Unorm);
    scene.samples = samples;
    scene.scissor = scissor;
    scene.viewport = viewport;
    Draw draw;
    draw.state = always_state();
    draw.positions_clip = {{-3, -3, 0.5f, 1}, {3, -3, 0.5f, 1}, {-3, 3, 0.5f, 1},
                           {3, -3, 0.5f, 1},  {3, 3, 0.5f, 1},  {-3, 3, 0.5f, 1}};
    scene.draws.push_back(draw);
    std::string report;
    const DiffFigures f = run_differential(scene, CpuVariant{}, report);
    totals().add(f);
    EXPECT_EQ(f.coverage_mismatches, 0u) << scene.name << ": first differences\n" << report;
    EXPECT_EQ(f.depth_mismatches, 0u) << scene.name << ": first differences\n" << report;
  }
};

TEST_F(DifferentialRegion, EmptyScissor) { expect_match("empty_scissor", Rect2D{5, 3, 0, 4}, std::nullopt); }

TEST_F(DifferentialRegion, ScissorOutsideTheFramebuffer) {
  expect_match("scissor_outside", Rect2D{40, 2, 10, 10}, std::nullopt);
}

TEST_F(DifferentialRegion, ViewportOutsideTheFramebuffer) {
  expect_match("viewport_outside", std::nullopt, Viewport{-50, 4, 20, 8, 0, 1});
}

TEST_F(DifferentialRegion, ViewportLargerThanTheFramebuffer) {
  expect_match("viewport_larger", Rect2D{3, 1, 20, 30}, Viewport{-7.25f, -3.5f, 50.5f, 30.75f, 0.25f, 0.75f});
}

// The same with 4x multisampling, where lavapipe draws nothing into an empty region although its
// multisample left/top scissor planes would pass samples of the column and row before it (§2.5).
TEST_F(DifferentialRegion, EmptyScissorsMultisampled) {
  expect_match("empty_scissor_width_4x", Rect2D{5, 3, 0, 4}, std::nullopt, 4);
  expect_match("empty_scissor_height_4x", Rect2D{5, 3, 9, 0}, std::nullopt, 4);
}

TEST_F(DifferentialRegion, ViewportRoundingToNoPixelMultisampled) {
  expect_match("viewport_rounds_to_empty_4x", std::nullopt, Viewport{5.6f, 4.6f, 0.8f, 0.8f, 0, 1}, 4);
  expect_match("viewport_rounds_to_empty_wide_4x", std::nullopt, Viewport{2.5f, 4.7f, 20.25f, 0.75f, 0, 1}, 4);
}

std::string case_name(const ::testing::TestParamInfo<Differential::ParamType>& info) {
  return std::string(std::get<0>(info.param).name) + "_seed" + std::to_string(std::get<1>(info.param));
}

Scene rectangular_lines(uint32_t seed) { return line_scene(seed, LineMode::Default); }
Scene bresenham_lines(uint32_t seed) { return line_scene(seed, LineMode::Bresenham); }
Scene msaa_rectangular_lines(uint32_t seed) { return line_scene(seed, LineMode::Rectangular, 4); }
Scene msaa_bresenham_lines(uint32_t seed) { return line_scene(seed, LineMode::Bresenham, 4); }
Scene grid(uint32_t seed) { return grid_triangles(seed); }

using ::testing::Combine;
using ::testing::Range;
using ::testing::Values;

INSTANTIATE_TEST_SUITE_P(Grid, Differential, Combine(Values(Family{"grid", grid}), Range(1u, 13u)), case_name);
INSTANTIATE_TEST_SUITE_P(Perspective, Differential,
                         Combine(Values(Family{"perspective", perspective_triangles}), Range(1u, 11u)), case_name);
INSTANTIATE_TEST_SUITE_P(Clipped, Differential, Combine(Values(Family{"clipped", clipped_triangles}), Range(1u, 11u)),
                         case_name);
INSTANTIATE_TEST_SUITE_P(Sliver, Differential, Combine(Values(Family{"sliver", sliver_triangles}), Range(1u, 6u)),
                         case_name);
INSTANTIATE_TEST_SUITE_P(Far, Differential, Combine(Values(Family{"far", far_triangles}), Range(1u, 5u)), case_name);
INSTANTIATE_TEST_SUITE_P(BiasCull, Differential,
                         Combine(Values(Family{"bias_cull", bias_cull_triangles}), Range(1u, 11u)), case_name);
INSTANTIATE_TEST_SUITE_P(ClampScissor, Differential,
                         Combine(Values(Family{"clamp_scissor", clamp_scissor_triangles}), Range(1u, 11u)), case_name);
INSTANTIATE_TEST_SUITE_P(Multi, Differential, Combine(Values(Family{"multi", multi_triangle_draws}), Range(1u, 11u)),
                         case_name);
INSTANTIATE_TEST_SUITE_P(RectangularLines, Differential,
                         Combine(Values(Family{"lines_rectangular", rectangular_lines}), Range(1u, 9u)), case_name);
INSTANTIATE_TEST_SUITE_P(BresenhamLines, Differential,
                         Combine(Values(Family{"lines_bresenham", bresenham_lines}), Range(1u, 9u)), case_name);
INSTANTIATE_TEST_SUITE_P(CentredBresenhamLines, Differential,
                         Combine(Values(Family{"lines_bresenham_centred", centred_bresenham_lines}), Range(1u, 5u)),
                         case_name);
INSTANTIATE_TEST_SUITE_P(LatticeBresenhamLines, Differential,
                         Combine(Values(Family{"lines_bresenham_lattice", lattice_bresenham_lines}), Range(1u, 7u)),
                         case_name);
INSTANTIATE_TEST_SUITE_P(Chunks, Differential, Combine(Values(Family{"chunks", chunked_draws}), Range(1u, 7u)),
                         case_name);
INSTANTIATE_TEST_SUITE_P(StripsFans, Differential,
                         Combine(Values(Family{"strips_fans", strips_and_fans}), Range(1u, 6u)), case_name);
INSTANTIATE_TEST_SUITE_P(Msaa, Differential, Combine(Values(Family{"msaa", msaa_triangles}), Range(1u, 9u)), case_name);
INSTANTIATE_TEST_SUITE_P(MsaaLines, Differential,
                         Combine(Values(Family{"msaa_lines_rectangular", msaa_rectangular_lines},
                                        Family{"msaa_lines_bresenham", msaa_bresenham_lines}),
                                 Range(1u, 7u)),
                         case_name);
INSTANTIATE_TEST_SUITE_P(Less, Differential, Combine(Values(Family{"less", less_triangles}), Range(1u, 6u)), case_name);
INSTANTIATE_TEST_SUITE_P(MsaaBresenhamDepth, Differential,
                         Combine(Values(Family{"msaa_bresenham_depth", msaa_bresenham_depth}), Range(1u, 7u)),
                         case_name);
INSTANTIATE_TEST_SUITE_P(MsaaLess, Differential,
                         Combine(Values(Family{"msaa_less", msaa_less_triangles}), Range(1u, 7u)), case_name);
INSTANTIATE_TEST_SUITE_P(Viewport, Differential, Combine(Values(Family{"viewport", viewport_triangles}), Range(1u, 9u)),
                         case_name);

}  // namespace
}  // namespace rastercmp::differential
