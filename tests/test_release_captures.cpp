// The lavapipe profile against every modelled Mesa release, without the release installed: renders
// recorded on each release's lavapipe (tests/captures/lavapipe-X.Y.Z/, made with
// scripts/debian-root.sh --capture) judged with `conformance --captures`, the rules chosen from the
// driver each render.json names (docs/lavapipe-rules.md §8). The built-in suite and a soak slice
// pass with the release's own rules and fail with another's where the releases differ, so the
// version switch is exercised on every host; a driver of an unmodelled release is judged by the
// nearest one with a warning in every output.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "tests/test_cli_support.hpp"

namespace rastercmp {
namespace {

using namespace cli_test;

const fs::path kCaptures = kSourceDir / "tests" / "captures";
const std::vector<std::string> kReleases = {"22.3.6", "25.0.7", "26.2.6"};

// The sanitizer build (make test's second pass) judges one case in kShards of the suite and of the
// soak slices, and a third of the pinning pairs: the Release pass judges them all, and a part takes
// the sanitizers through the same code (docs/reliability.md, "Cost").
#ifdef RASTERCMP_SANITIZER_BUILD
constexpr int kShards = 8;
#else
constexpr int kShards = 1;
#endif
const std::string kShard = "0/" + std::to_string(kShards);

fs::path release_dir(const std::string& release) { return kCaptures / ("lavapipe-" + release); }

// conformance over a release's recorded suite or soak slice; `profile` as on the command line.
RunResult judge_suite(const std::string& release, const std::string& profile, const fs::path& out) {
  return run_cli({"conformance", "--suite", (kSourceDir / "scenes").string(), "--captures",
                  (release_dir(release) / "suite").string(), "--baseline",
                  (kSourceDir / "scenes" / "methods" / "expected-failures.txt").string(), "--profile", profile,
                  "--shard", kShard, "--out", out.string()},
                 kNoVulkanLoader);
}

RunResult judge_soak(const std::string& release, const std::string& profile, const fs::path& out) {
  return run_cli({"conformance", "--suite", (release_dir(release) / "soak" / "scenes").string(), "--captures",
                  (release_dir(release) / "soak" / "renders").string(), "--profile", profile, "--shard", kShard,
                  "--out", out.string()},
                 kNoVulkanLoader);
}

// The cases failures.csv names (name,Status lines).
std::set<std::string> failing_cases(const fs::path& out) {
  std::set<std::string> names;
  for (const std::string& line : lines_of(read_file(out / "failures.csv")))
    if (const auto comma = line.find(','); comma != std::string::npos) names.insert(line.substr(0, comma));
  return names;
}

std::string profile_of(const std::string& release) { return "lavapipe-" + release.substr(0, release.rfind('.')); }

// conformance --captures judges a scene without a capture as a ResourceError, which the methods'
// baseline accepts for its scenes: a scene added without recording it on every release would pass
// unjudged. Each scene file of scenes/ has its capture folder (its path without ".json", holding
// render.json) on every release, and every capture folder a scene.
TEST(ReleaseCaptures, EveryBuiltInSceneHasACaptureOnEveryRelease) {
  const fs::path scenes = kSourceDir / "scenes";
  std::set<std::string> scene_cases;
  for (const auto& entry : fs::recursive_directory_iterator(scenes))
    if (entry.is_regular_file() && entry.path().extension() == ".json")
      scene_cases.insert(fs::relative(entry.path(), scenes).replace_extension().generic_string());
  ASSERT_GT(scene_cases.size(), 150u);
  for (const std::string& release : kReleases) {
    SCOPED_TRACE(release);
    const fs::path suite = release_dir(release) / "suite";
    std::set<std::string> captured;
    for (const auto& entry : fs::recursive_directory_iterator(suite))
      if (entry.is_regular_file() && entry.path().filename() == "render.json")
        captured.insert(fs::relative(entry.path().parent_path(), suite).generic_string());
    for (const std::string& name : scene_cases)
      EXPECT_TRUE(captured.count(name)) << "scenes/" << name << ".json has no capture in " << suite
                                        << " (tests/captures/README.md, \"Recording them again\")";
    for (const std::string& name : captured)
      EXPECT_TRUE(scene_cases.count(name)) << suite / name << " is the capture of no scene of scenes/";
  }
}

TEST(ReleaseCaptures, EachReleasePassesWithTheRulesOfItsDriver) {
  for (const std::string& release : kReleases) {
    SCOPED_TRACE(release);
    ASSERT_TRUE(fs::is_directory(release_dir(release))) << release_dir(release);
    const TempDir tmp;
    const RunResult suite = judge_suite(release, "lavapipe", tmp / "suite");
    EXPECT_EQ(suite.exit_code, 0)
        << "re-capture after changing a scene: scripts/debian-root.sh, tests/captures/README.md\n"
        << describe({"conformance", "(suite)"}, suite);
    EXPECT_NE(suite.out.find(profile_of(release) + " profile"), std::string::npos) << suite.out;
    const nlohmann::json summary = nlohmann::json::parse(read_file(tmp / "suite" / "summary.json"));
    EXPECT_EQ(summary.at("profile"), profile_of(release));
    EXPECT_FALSE(summary.contains("profile_warning"));
    const RunResult soak = judge_soak(release, "lavapipe", tmp / "soak");
    EXPECT_EQ(soak.exit_code, 0) << describe({"conformance", "(soak slice)"}, soak);
  }
}

// The scenes that pin one rule each (docs/suite.md "Mesa releases"), with the first modelled
// release that follows it: judged by a release on the other side of that change, the scene fails,
// and on the same side it passes.
struct Pin {
  std::string scene;
  std::string from;  // the first modelled release with the new rule
};
const std::vector<Pin> kPins = {
    {"rastercmp.release.line_snap_tie", "25.0.7"},
    {"rastercmp.release.bresenham_width_tie", "25.0.7"},
    {"rastercmp.release.bresenham_end_on_pixel_centre", "25.0.7"},
    {"rastercmp.release.wide_line_outside_viewport", "25.0.7"},
    {"rastercmp.release.msaa_wide_line_depth", "26.2.6"},
    {"rastercmp.depth.bias.d16_unorm.constant", "26.2.6"},
    {"rastercmp.depth.bias.x8_d24_unorm.constant", "26.2.6"},
    {"rastercmp.msaa.scissor.inner", "26.2.6"},
};

size_t release_index(const std::string& release) {
  return size_t(std::find(kReleases.begin(), kReleases.end(), release) - kReleases.begin());
}

TEST(ReleaseCaptures, EachPinningSceneFailsExactlyUnderTheRulesAcrossItsChange) {
  for (const std::string& captured : kReleases) {
    for (const std::string& judged_by : kReleases) {
      // The sanitizer build judges each release's captures by the next release's rules only (3 of
      // the 9 pairs, with pins that pass and pins that fail in each); the Release pass judges all.
      if (kShards > 1 && release_index(judged_by) != (release_index(captured) + 1) % kReleases.size()) continue;
      SCOPED_TRACE(captured + " judged by " + profile_of(judged_by));
      std::vector<std::string> args = {"conformance",
                                       "--suite",
                                       (kSourceDir / "scenes").string(),
                                       "--captures",
                                       (release_dir(captured) / "suite").string(),
                                       "--profile",
                                       profile_of(judged_by),
                                       "--flake-retries",
                                       "0"};
      std::set<std::string> expected;
      for (const Pin& pin : kPins) {
        args.insert(args.end(), {"--case", pin.scene});
        const size_t from = release_index(pin.from);
        if ((release_index(captured) >= from) != (release_index(judged_by) >= from)) expected.insert(pin.scene);
      }
      const TempDir tmp;
      args.insert(args.end(), {"--out", (tmp / "out").string()});
      const RunResult r = run_cli(args, kNoVulkanLoader);
      EXPECT_EQ(r.exit_code, expected.empty() ? 0 : 1) << describe(args, r);
      EXPECT_EQ(failing_cases(tmp / "out"), expected);
    }
  }
}

// A soak slice is the scenes on which its driver and another release's rules differ: under those
// rules each fails.
TEST(ReleaseCaptures, SoakSlicesFailUnderAnotherReleasesRules) {
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"22.3.6", "lavapipe-25.0"}, {"25.0.7", "lavapipe-22.3"}, {"26.2.6", "lavapipe-22.3"}};
  for (const auto& [captured, judged_by] : pairs) {
    SCOPED_TRACE(captured + " judged by " + judged_by);
    const TempDir tmp;
    const RunResult r = run_cli({"conformance", "--suite", (release_dir(captured) / "soak" / "scenes").string(),
                                 "--captures", (release_dir(captured) / "soak" / "renders").string(), "--profile",
                                 judged_by, "--flake-retries", "0", "--shard", kShard, "--out", (tmp / "out").string()},
                                kNoVulkanLoader);
    EXPECT_EQ(r.exit_code, 1) << describe({"conformance", "(soak slice)"}, r);
    const size_t judged = lines_of(read_file(tmp / "out" / "results.csv")).size();
    EXPECT_GT(judged, 10u);
    EXPECT_EQ(failing_cases(tmp / "out").size(), judged);
  }
}

// A render.json naming a release the profile does not model: judged by the nearest, and the
// console, summary.json and the report say so.
TEST(ReleaseCaptures, AnUnmodelledReleaseIsJudgedByTheNearestWithAWarning) {
  const TempDir tmp;
  const fs::path scene = kSourceDir / "scenes" / "line" / "clipped" / "bresenham_w1.json";
  const fs::path recorded = release_dir("25.0.7") / "suite" / "line" / "clipped" / "bresenham_w1";
  const fs::path suite = tmp / "suite", captures = tmp / "captures";
  fs::create_directories(suite);
  fs::copy_file(scene, suite / "bresenham_w1.json");
  fs::create_directories(captures / "bresenham_w1");
  fs::copy(recorded, captures / "bresenham_w1");
  nlohmann::json render = nlohmann::json::parse(read_file(captures / "bresenham_w1" / "render.json"));
  render["driver"] = "Mesa 24.1.7 (LLVM 17.0.6)";
  write_file(captures / "bresenham_w1" / "render.json", render.dump(2));
  const RunResult r = run_cli(
      {"conformance", "--suite", suite.string(), "--captures", captures.string(), "--out", (tmp / "out").string()},
      kNoVulkanLoader);
  EXPECT_EQ(r.exit_code, 0) << describe({"conformance"}, r);  // 24.1 is nearest to 25.0, whose lines these are
  const std::string warning = "lavapipe Mesa 24.1.7 is not a modelled release: judged by lavapipe-25.0";
  EXPECT_NE(r.out.find(warning), std::string::npos) << r.out;
  const nlohmann::json summary = nlohmann::json::parse(read_file(tmp / "out" / "summary.json"));
  EXPECT_EQ(summary.at("profile"), "lavapipe-25.0");
  EXPECT_NE(summary.value("profile_warning", std::string()).find(warning), std::string::npos);
  EXPECT_NE(read_file(tmp / "out" / "report" / "index.html").find(warning), std::string::npos);
}

}  // namespace
}  // namespace rastercmp
