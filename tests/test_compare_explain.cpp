// compare/explain_text: the explain text of a sample (CPU history, both final values, the
// classification) and the report's explanation files for the first bad samples.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "compare/explain_text.hpp"
#include "compare/report.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/scene_io.hpp"
#include "test_spec_support.hpp"

namespace rastercmp {
namespace {
namespace fs = std::filesystem;

const char* kScene = R"({
  "name": "rcmptest.explain.two", "width": 16, "height": 12, "depth_format": "d16_unorm", "space": "pixels",
  "draws": [{"positions": [[1.0, 1.0, 0.5], [15.0, 1.5, 0.5], [2.0, 11.0, 0.5]]},
            {"positions": [[4.0, 2.0, 0.25], [12.0, 3.0, 0.25], [6.0, 10.0, 0.25]]}]
})";

CpuOptions cpu_options() {
  CpuOptions cpu;
  cpu.fma = lavapipe_fuses_on_this_host();
  return cpu;
}

// The CPU render as expected; the "actual" render is the same with planted differences.
struct Planted {
  Scene scene = parse_scene(kScene, "explain_test.json");
  CaseResult result;
  Planted() {
    result.expected = render_cpu(scene, cpu_options());
    result.actual = result.expected;
    result.actual->owner[result.actual->index(6, 4)] = kOwnerBackground;  // missing
    result.actual->depth_raw[result.actual->index(2, 2)] += 3;            // depth off by 3 LSB
    result.diff = diff_results(*result.expected, *result.actual, CompareProfile::Lavapipe);
    result.verdict = Verdict::Fail;
  }
};

TEST(ExplainText, ShowsTheHistoryBothValuesAndTheClass) {
  const Planted p;
  ASSERT_NE(p.result.expected->owner[p.result.expected->index(6, 4)], kOwnerBackground) << "the scene changed";
  const std::string missing = explain_sample_text(p.scene, cpu_options(), *p.result.expected, *p.result.actual,
                                                  CompareProfile::Lavapipe, 6, 4, 0);
  EXPECT_NE(missing.find("pixel (6, 4) sample 0"), std::string::npos) << missing;
  EXPECT_NE(missing.find("Vulkan device (judged):      owner background"), std::string::npos) << missing;
  EXPECT_NE(missing.find("CPU exact model (reference): owner draw 1 primitive 0"), std::string::npos) << missing;
  EXPECT_NE(missing.find("classification:              missing (the judged renderer lacks it)\n"), std::string::npos)
      << missing;
  const std::string depth = explain_sample_text(p.scene, cpu_options(), *p.result.expected, *p.result.actual,
                                                CompareProfile::Lavapipe, 2, 2, 0);
  EXPECT_NE(depth.find("classification:              depth off by 3 LSB (1.5 r)\n"), std::string::npos) << depth;
  const std::string match = explain_sample_text(p.scene, cpu_options(), *p.result.expected, *p.result.actual,
                                                CompareProfile::Lavapipe, 0, 11, 0);
  EXPECT_NE(match.find("classification:              match\n"), std::string::npos) << match;
  // Under a classic method the CPU is judged: the sample only the CPU covers is one it adds.
  CpuOptions method = cpu_options();
  method.methods = {{"tie_break", "none"}};
  const std::string judged_cpu =
      explain_sample_text(p.scene, method, *p.result.expected, *p.result.actual, CompareProfile::Lavapipe, 6, 4, 0);
  EXPECT_NE(judged_cpu.find("CPU tie_break=none (judged): owner draw 1 primitive 0"), std::string::npos) << judged_cpu;
  EXPECT_NE(judged_cpu.find("Vulkan device (reference):   owner background"), std::string::npos) << judged_cpu;
  // The word is the judged renderer's: the CPU method adds the fragment, so it is unexpected.
  EXPECT_NE(judged_cpu.find("classification:              unexpected (the judged renderer adds it)\n"),
            std::string::npos)
      << judged_cpu;
  EXPECT_EQ(judged_cpu.find("missing"), std::string::npos) << judged_cpu;
}

TEST(ExplainText, ReportGetsFilesForTheFirstBadSamples) {
  const Planted p;
  const fs::path dir = fs::temp_directory_path() / ("rastercmp_test_compare_explain_" + std::to_string(getpid()));
  fs::remove_all(dir);
  const auto links =
      write_case_explanations(dir.string(), p.scene.name, p.scene, cpu_options(), p.result, CompareProfile::Lavapipe);
  ASSERT_EQ(links.size(), 2u);  // two bad samples, in scan order
  EXPECT_EQ(links[0].at, (SampleLocation{2, 2, 0}));
  EXPECT_EQ(links[0].file, case_folder(p.scene.name) + "/explain_2_2_s0.txt");
  EXPECT_EQ(links[1].at, (SampleLocation{6, 4, 0}));
  for (const ExplainLink& link : links) EXPECT_TRUE(fs::exists(dir / link.file)) << link.file;
  CaseResult unsupported;
  unsupported.verdict = Verdict::NotSupported;
  EXPECT_TRUE(write_case_explanations(dir.string(), "x", p.scene, cpu_options(), unsupported, CompareProfile::Lavapipe)
                  .empty());
  fs::remove_all(dir);
}

// Every scene of scenes/methods/ with its own methods: a planted bad sample gets the classic
// path's history in its report file, never "not available".
TEST(ExplainText, ClassicMethodScenesGetTheirMethodsHistory) {
  const fs::path dir = fs::temp_directory_path() / ("rastercmp_test_compare_explain_m" + std::to_string(getpid()));
  fs::remove_all(dir);
  size_t scenes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(std::string(RASTERCMP_SOURCE_DIR) + "/scenes/methods")) {
    if (entry.path().extension() != ".json") continue;
    const Scene scene = load_scene_file(entry.path().string());
    CpuOptions cpu = cpu_options();
    cpu.methods = scene.methods;
    CaseResult result;
    result.expected = render_cpu(scene, cpu);
    result.actual = result.expected;
    size_t planted = 0;
    while (planted < result.actual->owner.size() && result.actual->owner[planted] == kOwnerBackground) ++planted;
    const bool draws = planted < result.actual->owner.size();  // cull/normal_dot_view/back culls everything
    if (draws)
      result.actual->owner[planted] = kOwnerBackground;
    else
      result.actual->owner[0] = encode_owner(0, 0);
    result.diff = diff_results(*result.expected, *result.actual, CompareProfile::Lavapipe);
    result.verdict = Verdict::Fail;
    const auto links = write_case_explanations(dir.string(), scene.name, scene, cpu, result, CompareProfile::Lavapipe);
    ASSERT_EQ(links.size(), 1u) << scene.name;
    std::ifstream in(dir / links[0].file);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str().find("not available"), std::string::npos) << text.str();
    EXPECT_NE(text.str().find("classic path, methods"), std::string::npos) << text.str();
    EXPECT_EQ(draws, text.str().find("owner written") != std::string::npos) << text.str();
    ++scenes;
  }
  EXPECT_GE(scenes, 38u);
  fs::remove_all(dir);
}

// Spec profile: the owner alternatives (docs/spec-profile.md "Owners") on the diagonal quad of
// tests/test_spec_owners.cpp, two coplanar triangles with other vertices whose common diagonal
// x + y = 14 runs through the centres of the pixels x + y = 13: there the tie rule picks the owner,
// so the other triangle is an alternative (left by the bottom-right rule); off it there is none.
TEST(ExplainText, SpecProfileNamesTheOwnerAlternatives) {
  Scene scene = spec_test::make_scene(16, 16);
  scene.draws.push_back(spec_test::window_triangles(scene, {{2, 2}, {12, 2}, {2, 12}, {12, 2}, {12, 12}, {2, 12}}));
  const CpuOptions cpu = spec_test::spec_options();
  const RenderResult expected = render_cpu(scene, cpu);
  const size_t tie = expected.index(5, 8), inside = expected.index(4, 4);
  ASSERT_EQ(expected.coverage_class[tie], CoverageClass::Must);
  ASSERT_EQ(expected.owner[inside], encode_owner(0, 0)) << "the scene changed";
  const uint32_t other = expected.owner[tie] == encode_owner(0, 0) ? encode_owner(0, 1) : encode_owner(0, 0);
  RenderResult actual = expected;
  actual.owner[tie] = other;                  // an allowed owner
  actual.owner[inside] = encode_owner(0, 1);  // a wrong owner: no device leaves the second triangle there
  const auto explain = [&](uint32_t x, uint32_t y) {
    return explain_sample_text(scene, cpu, expected, actual, CompareProfile::Spec, x, y, 0);
  };
  const std::string named = fmt::format("draw 0 primitive {} (id {:#010x})", owner_primitive(other), other);
  const std::string allowed = explain(5, 8);
  EXPECT_NE(allowed.find("spec owners (docs/spec-profile.md, Owners):\n  estimate:     draw 0 primitive"),
            std::string::npos)
      << allowed;
  EXPECT_NE(allowed.find("  alternatives: " + named +
                         ": a device with nearest vertex rounding, bottom-right tie "
                         "rule, D32 rounding nearest leaves it (and 2 other devices)\n"),
            std::string::npos)
      << allowed;
  EXPECT_NE(allowed.find("  observed:     " + named + ": an allowed alternative (Pass): a device with"),
            std::string::npos)
      << allowed;
  const std::string wrong = explain(4, 4);
  EXPECT_NE(wrong.find("  alternatives: none"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("neither the estimate's nor an allowed alternative (wrong owner, QualityWarning"),
            std::string::npos)
      << wrong;
  const std::string same = explain(9, 9);
  EXPECT_NE(same.find("  alternatives: none"), std::string::npos) << same;
  EXPECT_NE(same.find(": the estimate's\n"), std::string::npos) << same;
  // The lavapipe profile has no alternatives to show.
  EXPECT_EQ(explain_sample_text(scene, cpu, expected, actual, CompareProfile::Lavapipe, 5, 8, 0).find("spec owners"),
            std::string::npos);
}

// Spec profile: the class of the sample, the limits it was judged with and each nearby primitive's
// own class there, so that a driver developer can argue with a MustNot. A triangle of the quad
// above and a width-1 line across row 3, 0.2 px above the centres: (1, 8) is MustNot with nothing
// near, (10, 10) MustNot inside the triangle's bounds (it misses the box under every placement of
// its vertices), (4, 4) Must, (6, 3) open for its owner, which the line may be; with
// viewportSubPixelBits 0 a viewport with fractional bounds is judged in each of its representations.
TEST(ExplainText, SpecProfileExplainsTheClassAndTheLimits) {
  Scene scene = spec_test::make_scene(16, 16);
  scene.draws.push_back(spec_test::window_triangles(scene, {{2, 2}, {12, 2}, {2, 12}}));
  Draw line = spec_test::window_triangles(scene, {{3.5, 3.3}, {14.5, 3.3}});
  line.topology = Topology::LineList;
  scene.draws.push_back(line);
  CpuOptions cpu = spec_test::spec_options(4);
  cpu.viewport_sub_pixel_bits = 0;
  const RenderResult expected = render_cpu(scene, cpu);
  const auto explain = [&](uint32_t x, uint32_t y) {
    return explain_sample_text(scene, cpu, expected, expected, CompareProfile::Spec, x, y, 0);
  };
  const std::string nothing = explain(1, 8);
  EXPECT_NE(nothing.find("  why:          no primitive reaches the pixel"), std::string::npos) << nothing;
  const std::string must_not = explain(10, 10);
  EXPECT_NE(must_not.find("spec class (docs/spec-profile.md): MustNot\n  limits:       subPixelPrecisionBits 4, "
                          "viewportSubPixelBits 0 (0 other viewport representation(s)"),
            std::string::npos)
      << must_not;
  EXPECT_NE(must_not.find("draw 0 primitive 0 (id 0x00000000) (triangle piece): none, gate never"), std::string::npos)
      << must_not;
  EXPECT_NE(must_not.find("  why:          no primitive may cover it"), std::string::npos) << must_not;
  const std::string must = explain(4, 4);
  EXPECT_NE(must.find("spec class (docs/spec-profile.md): Must\n"), std::string::npos) << must;
  EXPECT_NE(must.find("(triangle piece): full, gate certain"), std::string::npos) << must;
  const std::string near_line = explain(6, 3);
  EXPECT_NE(near_line.find("(line): partial, gate certain"), std::string::npos) << near_line;
  EXPECT_NE(near_line.find("  owner open:   a line may cover the pixel"), std::string::npos) << near_line;
  scene.viewport = Viewport{0.25f, 0, 15.5f, 16, 0, 1};
  const RenderResult fractional = render_cpu(scene, cpu);
  const std::string held = explain_sample_text(scene, cpu, fractional, fractional, CompareProfile::Spec, 1, 8, 0);
  EXPECT_NE(held.find("viewportSubPixelBits 0 (4 other viewport representation(s)"), std::string::npos) << held;
}

}  // namespace
}  // namespace rastercmp
