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
  EXPECT_NE(judged_cpu.find("missing (the judged renderer adds it)"), std::string::npos) << judged_cpu;
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

}  // namespace
}  // namespace rastercmp
