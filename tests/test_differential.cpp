// The CPU lavapipe profile against lavapipe itself, sample by sample: every owner id and every raw
// depth value must be equal (docs/lavapipe-rules.md "Tolerances": 0 and 0). Seeded random scenes,
// the seed in each test's name. Validation layer on, zero messages. Skips only without a device.
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "compare/diff.hpp"
#include "compare/verdict.hpp"
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

// 4x depth compared per sample (issue #19): a steep plane (depth from 0.02 at the left edge to
// 0.98 at the right, plus a tilt in y) so the four samples of nearly every pixel hold different
// depths, crossed by a second plane under LESS so per-sample depth also decides ownership. The
// Vulkan side must read back every sample's raw depth, and it must equal the CPU's, in each format.
TEST_F(DifferentialRegion, Msaa4xSteepPlaneDepthMatchesPerSample) {
  for (const DepthFormat format : {DepthFormat::D16Unorm, DepthFormat::X8D24Unorm, DepthFormat::D32Sfloat}) {
    SCOPED_TRACE(to_string(format));
    Scene scene =
        make_scene(fmt::format("rastercmp.differential.msaa_steep_depth.{}", to_string(format)), 64, 32, format);
    scene.samples = 4;
    Draw steep;
    steep.positions_clip = {{-1, -1, 0.02f, 1}, {1, -1, 0.9f, 1}, {-1, 1, 0.1f, 1},
                            {1, -1, 0.9f, 1},   {1, 1, 0.98f, 1}, {-1, 1, 0.1f, 1}};
    Draw crossing;  // tilted the other way, perspective (w != 1): crosses the steep plane
    crossing.positions_clip = {{-1.5f, -1.5f, 1.35f, 1.5f}, {2, -2, 0.2f, 2}, {-1.25f, 1.25f, 1.1f, 1.25f}};
    scene.draws = {steep, crossing};
    std::string report;
    const DiffFigures f = run_differential(scene, CpuVariant{}, report);
    totals().add(f);
    const RenderResult vk = shared_renderer().render(scene);
    ASSERT_TRUE(vk.has_depth()) << "4x depth not read back";
    uint32_t pixels_with_distinct_depths = 0, pixels_of_both_draws = 0;
    for (uint32_t y = 0; y < scene.height; ++y) {
      for (uint32_t x = 0; x < scene.width; ++x) {
        const size_t first = vk.index(x, y, 0);
        bool distinct = false, mixed = false;
        for (uint32_t s = 1; s < 4; ++s) {
          distinct |= vk.depth_raw[first + s] != vk.depth_raw[first];
          mixed |= owner_draw(vk.owner[first + s]) != owner_draw(vk.owner[first]);
        }
        pixels_with_distinct_depths += distinct;
        pixels_of_both_draws += mixed;
      }
    }
    EXPECT_GT(pixels_with_distinct_depths, scene.width * scene.height * 9 / 10) << "the plane is not steep enough";
    EXPECT_GT(pixels_of_both_draws, 0u) << "the planes do not cross within a pixel";
    EXPECT_EQ(f.coverage_mismatches, 0u) << scene.name << ": first differences\n" << report;
    EXPECT_EQ(f.depth_mismatches, 0u) << scene.name << ": first differences\n" << report;
  }
}

// The same 4x scene through compare/ (what `rastercmp conformance` runs): the driver's per-sample
// depth is compared, the unchanged renders pass without "depth not compared", and one Vulkan
// sample's depth nudged by one unit is reported as exactly one depth mismatch at that sample.
TEST_F(DifferentialRegion, Msaa4xDepthPerturbationIsADepthMismatchInTheDiff) {
  Scene scene = make_scene("rastercmp.differential.msaa_depth_perturbed", 32, 16, DepthFormat::X8D24Unorm);
  scene.samples = 4;
  Draw steep;
  steep.positions_clip = {{-1, -1, 0.1f, 1}, {1, -1, 0.9f, 1}, {-1, 1, 0.2f, 1}};
  scene.draws.push_back(steep);
  CpuOptions options;
  options.fma = shared_renderer().device().fma;
  options.lavapipe = &test::release_of(shared_renderer());
  const RenderResult cpu = render_cpu(scene, options);
  RenderResult vk = shared_renderer().render(scene);
  for (const std::string& m : shared_renderer().validation_messages()) ADD_FAILURE() << "validation: " << m;
  ASSERT_TRUE(vk.has_depth());
  const SceneDiff same = rastercmp::diff_results(cpu, vk, CompareProfile::Lavapipe);
  EXPECT_TRUE(same.summary.depth_compared);
  EXPECT_EQ(same.summary.depth.mismatches, 0u);
  const VerdictDecision pass = decide_verdict(same.summary, 0);
  EXPECT_EQ(pass.verdict, Verdict::Pass) << pass.message;
  EXPECT_EQ(pass.message.find("depth not compared"), std::string::npos) << pass.message;

  const SampleLocation at{5, 3, 2};  // inside the triangle
  const size_t i = vk.index(at.x, at.y, at.sample);
  ASSERT_EQ(owner_draw(vk.owner[i]), 0u);
  vk.depth_raw[i] += 1;
  const SceneDiff perturbed = rastercmp::diff_results(cpu, vk, CompareProfile::Lavapipe);
  EXPECT_EQ(perturbed.summary.coverage_mismatches(), 0u);
  EXPECT_EQ(perturbed.summary.depth.mismatches, 1u);
  EXPECT_EQ(perturbed.summary.depth.max_at, at);
  EXPECT_EQ(perturbed.summary.depth.max_raw, 1u);
  EXPECT_EQ(decide_verdict(perturbed.summary, 0).verdict, Verdict::Fail);
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
