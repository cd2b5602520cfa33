// Conformance end to end on a small temporary suite rendered with lavapipe (validation on):
// statuses, outputs that parse, byte-identical results across runs and CPU thread counts,
// baselines, an interrupted run and its resumption, shards and their merge.
#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/detail/pugixml/pugixml.hpp>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "compare/case_run.hpp"
#include "compare/conformance.hpp"
#include "compare/merge.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace {
namespace fs = std::filesystem;

const char* kTriangle = R"({
  "name": "rcmptest.a.triangle", "width": 24, "height": 20, "depth_format": "x8_d24_unorm",
  "draws": [{"positions": [[-0.8, -0.7, 0.2], [0.9, -0.3, 0.6], [-0.1, 0.85, 0.9]]}]
})";
const char* kQuad = R"({
  "name": "rcmptest.b.quad", "width": 17, "height": 23, "depth_format": "d16_unorm", "space": "pixels",
  "draws": [{"topology": "triangle_strip",
             "positions": [[2.5, 3.25, 0.1], [14.75, 2.5, 0.3], [3.0, 20.5, 0.5], [15.5, 21.0, 0.7]]},
            {"depth_bias": {"constant": 2, "slope": 1},
             "positions": [[1.0, 1.0, 0.4], [16.0, 12.0, 0.4], [1.0, 22.0, 0.6]]}]
})";
const char* kPolygonLine = R"({
  "name": "rcmptest.c.polygon_line", "width": 16, "height": 16,
  "draws": [{"polygon_mode": "line", "positions": [[-0.8, -0.8, 0.5], [0.7, -0.6, 0.5], [-0.1, 0.8, 0.5]]}]
})";

// One folder per process: ctest runs the cases of this binary as parallel processes.
fs::path test_root() {
  return fs::temp_directory_path() / ("rastercmp_test_conformance_run_" + std::to_string(getpid()));
}

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

class ConformanceRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    fs::remove_all(test_root());
    write_file(test_root() / "suite/a/triangle.json", kTriangle);
    write_file(test_root() / "suite/b/quad.json", kQuad);
    write_file(test_root() / "suite/c/polygon_line.json", kPolygonLine);
    try {
      VulkanRenderer probe(VkOptions{"", true});
      has_vulkan_ = true;
    } catch (const EnvironmentError& e) {
      skip_reason_ = e.what();
    }
  }

  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(test_root(), ec);
  }

  void SetUp() override {
    if (!has_vulkan_) GTEST_SKIP() << "no Vulkan device: " << skip_reason_;
  }

  static ConformanceOptions options(const std::string& out, unsigned cpu_threads = 0) {
    ConformanceOptions o;
    o.suite_dir = (test_root() / "suite").string();
    o.out_dir = (test_root() / out).string();
    o.shard = Shard{0, 1};
    o.vk = VkOptions{"", true};
    o.cpu_options = [cpu_threads](const Scene&) {
      CpuOptions cpu;
      cpu.fma = lavapipe_fuses_on_this_host();
      cpu.threads = cpu_threads;
      return cpu;
    };
    // The cases run in children: the built executable (tests/CMakeLists.txt builds it first).
    o.worker_command = {(fs::path(RASTERCMP_BINARY_DIR) / "app" / "rastercmp").string(), "conformance-worker",
                        "--validate", "--threads", std::to_string(cpu_threads)};
    return o;
  }

  static ConformanceResult run(const ConformanceOptions& o, const ProgressFn& progress = {}) {
    std::atomic<int> stop{0};
    return run_conformance(o, plan_conformance(o), stop, progress);
  }

  // The deterministic outputs of a run folder.
  static void expect_same_outputs(const std::string& a, const std::string& b) {
    for (const char* file : {"summary.json", "failures.csv", "report/index.html"})
      EXPECT_EQ(read_file(test_root() / a / file), read_file(test_root() / b / file)) << file;
  }

  static inline bool has_vulkan_ = false;
  static inline std::string skip_reason_;
};

TEST_F(ConformanceRun, CaseRunnerRendersWithoutValidationMessages) {
  CaseRunner runner(CompareProfile::Lavapipe, options("unused").cpu_options, VkOptions{"", true});
  for (const char* file : {"suite/a/triangle.json", "suite/b/quad.json", "suite/c/polygon_line.json"}) {
    const CaseResult r = runner.run(load_scene_file((test_root() / file).string()));
    EXPECT_TRUE(r.validation_messages.empty()) << file << ": " << r.validation_messages.front();
    EXPECT_NE(r.verdict, Verdict::InternalError) << file << ": " << r.message;
  }
}

TEST_F(ConformanceRun, SmallSuitePassesWithOneNotSupported) {
  std::vector<std::string> progress;
  const ConformanceResult r = run(options("full"), [&](const std::string& line) { progress.push_back(line); });
  EXPECT_EQ(r.exit_code, 0);
  ASSERT_EQ(r.records.size(), 3u);
  EXPECT_EQ(r.records[0].status, "Pass") << r.records[0].message;
  EXPECT_EQ(r.records[1].status, "Pass") << r.records[1].message;
  EXPECT_EQ(r.records[2].status, "Skip");  // deqp-runner's name for NotSupported
  EXPECT_EQ(r.records[2].verdict, Verdict::NotSupported);
  EXPECT_EQ(r.records[2].message.rfind("cpu profile", 0), 0u) << r.records[2].message;
  ASSERT_EQ(progress.size(), 3u);
  EXPECT_EQ(progress[2].rfind("[3/3] rcmptest.c.polygon_line Skip", 0), 0u) << progress[2];

  const fs::path out = test_root() / "full";
  const auto durations = parse_results_csv(read_file(out / "results.csv"), "results.csv");
  EXPECT_EQ(durations.size(), 3u);
  EXPECT_EQ(read_file(out / "failures.csv"), "");
  pugi::xml_document junit;
  ASSERT_TRUE(junit.load_file((out / "junit.xml").c_str()));
  EXPECT_EQ(junit.child("testsuites").child("testsuite").attribute("tests").as_int(), 3);
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary["passed"], true);
  EXPECT_EQ(summary["complete"], true);
  EXPECT_EQ(summary["verdicts"]["NotSupported"], 1);
  EXPECT_EQ(summary["cases"][0]["coverage_mismatches"], 0);
  EXPECT_GT(summary["cases"][0]["covered_match"].get<int>(), 50);
  for (const char* image : {"cpu.png", "vulkan.png", "mask.png"})
    EXPECT_TRUE(fs::exists(out / "report/cases/rcmptest.b.quad" / image)) << image;
  // A pass has no depth difference, so no heatmap: its page says so.
  EXPECT_FALSE(fs::exists(out / "report/cases/rcmptest.b.quad/depth.png"));
  EXPECT_NE(read_file(out / "report/cases/rcmptest.b.quad/index.html").find("Depth identical"), std::string::npos);
  const std::string html = read_file(out / "report/index.html");
  EXPECT_NE(html.find("data-status=\"Skip\""), std::string::npos);
  EXPECT_NE(read_file(out / "report/cases/rcmptest.c.polygon_line/index.html").find("cpu profile"), std::string::npos);
}

TEST_F(ConformanceRun, OutputsAreByteIdenticalAcrossRunsAndThreadCounts) {
  run(options("det_exact", 0));
  run(options("det_threads", 2));
  expect_same_outputs("det_exact", "det_threads");
  for (const char* image : {"mask.png", "cpu.png", "index.html"})
    EXPECT_EQ(read_file(test_root() / "det_exact/report/cases/rcmptest.a.triangle" / image),
              read_file(test_root() / "det_threads/report/cases/rcmptest.a.triangle" / image))
        << image;
}

TEST_F(ConformanceRun, BaselineFlakesAndSkipsDecideTheExitCode) {
  write_file(test_root() / "fails.txt", "# expected to fail\nrcmptest.a.triangle,Fail\n");
  write_file(test_root() / "skips.txt", "polygon_line$\n");
  ConformanceOptions o = options("baseline");
  o.baseline_file = (test_root() / "fails.txt").string();
  o.skips_file = (test_root() / "skips.txt").string();
  const ConformanceResult improved = run(o);
  ASSERT_EQ(improved.records.size(), 3u);  // a case removed by --skips has a Skip row
  EXPECT_EQ(improved.records[0].status, "UnexpectedImprovement(Pass)");
  EXPECT_EQ(improved.records[2].status, "Skip");
  EXPECT_NE(improved.records[2].message.find("polygon_line$"), std::string::npos) << improved.records[2].message;
  EXPECT_EQ(improved.exit_code, 1);
  // failures.csv holds what failed the run, the improvement included.
  EXPECT_EQ(read_file(test_root() / "baseline/failures.csv"), "rcmptest.a.triangle,UnexpectedImprovement(Pass)\n");
  EXPECT_NE(read_file(test_root() / "baseline/results.csv").find("rcmptest.c.polygon_line,Skip,"), std::string::npos);
  write_file(test_root() / "flakes.txt", "rcmptest\\.a\\.\n");
  o.flakes_file = (test_root() / "flakes.txt").string();
  const ConformanceResult flaky = run(o);
  EXPECT_EQ(flaky.records[0].status, "KnownFlake");
  EXPECT_EQ(flaky.exit_code, 0);
}

TEST_F(ConformanceRun, SpecProfileRunsTheSameSuite) {
  ConformanceOptions o = options("spec");
  o.profile = CompareProfile::Spec;
  o.worker_command.insert(o.worker_command.end(), {"--profile", "spec"});
  const ConformanceResult r = run(o);
  EXPECT_EQ(r.info.profile, "spec");
  ASSERT_EQ(r.records.size(), 3u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(r.records[i].verdict, Verdict::Pass) << r.records[i].name << ": " << r.records[i].message;
    ASSERT_TRUE(r.records[i].diff.has_value());
    EXPECT_EQ(r.records[i].diff->profile, CompareProfile::Spec);
  }
  EXPECT_EQ(r.records[2].verdict, Verdict::NotSupported);
  EXPECT_EQ(r.exit_code, 0);
}

TEST_F(ConformanceRun, InterruptedRunWritesEverythingAndResumes) {
  std::atomic<int> stop{0};
  const ConformanceOptions o = options("interrupted");
  const ConformanceResult r =
      run_conformance(o, plan_conformance(o), stop, [&](const std::string&) { stop.store(SIGINT); });
  EXPECT_EQ(r.exit_code, kExitInterrupted);
  ASSERT_EQ(r.records.size(), 1u);
  const fs::path out = test_root() / "interrupted";
  // The finished case, then the two without a result as Missing.
  EXPECT_EQ(read_file(out / "results.csv").substr(read_file(out / "results.csv").find('\n') + 1),
            "rcmptest.b.quad,Missing,0.000\nrcmptest.c.polygon_line,Missing,0.000\n");
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary["interrupted"], true);
  EXPECT_EQ(summary["complete"], false);
  EXPECT_EQ(summary["passed"], false);
  EXPECT_EQ(summary["not_run"], (std::vector<std::string>{"rcmptest.b.quad", "rcmptest.c.polygon_line"}));
  ASSERT_TRUE(fs::exists(out / "not_run.txt"));

  ConformanceOptions resume = options("resumed");
  resume.caselist_file = (out / "not_run.txt").string();
  EXPECT_EQ(run(resume).records.size(), 2u);
  run(options("whole"));
  const MergeResult merged = merge_conformance_outputs((test_root() / "resume_merged").string(),
                                                       {out.string(), (test_root() / "resumed").string()});
  EXPECT_EQ(merged.exit_code, 0);
  expect_same_outputs("resume_merged", "whole");
}

// A stop that comes when every case has its result (the last case finishes after the signal, or
// the re-runs are cut) leaves nothing to resume: the run is complete, with the verdicts' exit,
// and no resume list (a resume of nothing failed, exit 2).
TEST_F(ConformanceRun, AStopAfterTheLastCaseLeavesACompleteRun) {
  std::atomic<int> stop{0};
  const ConformanceOptions o = options("late_stop");
  const ConformancePlan plan = plan_conformance(o);
  size_t finished = 0;
  const ConformanceResult r = run_conformance(o, plan, stop, [&](const std::string&) {
    if (++finished == plan.cases.size()) stop.store(SIGTERM);
  });
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(r.info.complete);
  EXPECT_FALSE(r.info.interrupted);
  const fs::path out = test_root() / "late_stop";
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary["complete"], true);
  EXPECT_EQ(summary["passed"], true);
  EXPECT_FALSE(fs::exists(out / "not_run.txt"));
}

TEST_F(ConformanceRun, ShardsMergeIntoTheWholeRun) {
  ConformanceOptions first = options("shard0"), second = options("shard1");
  first.shard = Shard{0, 2};
  second.shard = Shard{1, 2};
  const ConformanceResult a = run(first), b = run(second);
  ASSERT_EQ(a.records.size(), 2u);  // cases 0 and 2
  ASSERT_EQ(b.records.size(), 1u);  // case 1
  EXPECT_EQ(a.records[1].name, "rcmptest.c.polygon_line");
  EXPECT_EQ(b.records[0].name, "rcmptest.b.quad");
  run(options("whole_for_shards"));
  merge_conformance_outputs((test_root() / "shards_merged").string(),
                            {(test_root() / "shard0").string(), (test_root() / "shard1").string()});
  expect_same_outputs("shards_merged", "whole_for_shards");
  EXPECT_EQ(parse_results_csv(read_file(test_root() / "shards_merged/results.csv"), "results.csv").size(), 3u);
  // One shard of two is no whole run: refused, or with --allow-missing merged as incomplete,
  // the other shard's case Missing, and the run does not pass.
  EXPECT_THROW(merge_conformance_outputs((test_root() / "half_merged").string(), {(test_root() / "shard0").string()}),
               InputError);
  const MergeResult half =
      merge_conformance_outputs((test_root() / "half_merged").string(), {(test_root() / "shard0").string()}, true);
  EXPECT_EQ(half.exit_code, 1);
  EXPECT_FALSE(half.info.complete);
  EXPECT_EQ(half.info.missing_unnamed, 1u);
  const nlohmann::json summary = nlohmann::json::parse(read_file(test_root() / "half_merged/summary.json"));
  EXPECT_EQ(summary.at("passed"), false);
  EXPECT_EQ(summary.at("missing_unnamed"), 1);
  EXPECT_EQ(summary.at("statuses").at("Missing"), 1);
  EXPECT_EQ(nlohmann::json::parse(read_file(test_root() / "shard1/summary.json")).at("shard"), "1/2");
}

// Plans need no Vulkan device; their files go below the same per-process folder.
class PlanConformance : public ::testing::Test {
 protected:
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(test_root(), ec);
  }
};

// --out inside --suite: the run's output folder (it holds the lock file) is no part of the suite,
// so a second run does not read the first one's summary.json as a scene.
TEST_F(PlanConformance, AnOutputFolderInsideTheSuiteIsNoPartOfIt) {
  const fs::path suite = test_root() / "suite_with_out";
  fs::create_directories(suite);
  fs::copy_file(fs::path(RASTERCMP_SOURCE_DIR) / "scenes" / "triangle" / "sliver" / "long_thin.json",
                suite / "long_thin.json", fs::copy_options::overwrite_existing);
  write_file(suite / "out" / ".rastercmp.lock", "");
  write_file(suite / "out" / "summary.json", "{\"complete\": true}\n");
  write_file(suite / "out" / "report" / "cases" / "x" / "render.json", "{}\n");
  const std::vector<std::string> files = find_scene_files(suite.string());
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(fs::path(files[0]).filename(), "long_thin.json");
}

// A suite of suites: a link to another folder is followed (the build's suite/ links the built-in
// scenes beside the imported models), each real folder once, so a link cycle ends; model files
// count as scenes, except the importer's generic .xml and .raw (a junit.xml is no model).
TEST_F(PlanConformance, LinkedFoldersAreFollowedOnceAndModelFilesCount) {
  const fs::path root = test_root() / "linked_suites";
  fs::remove_all(root);
  fs::create_directories(root / "other");
  fs::create_directories(root / "suite");
  fs::copy_file(fs::path(RASTERCMP_SOURCE_DIR) / "scenes" / "triangle" / "sliver" / "long_thin.json",
                root / "other" / "long_thin.json");
  write_file(root / "other" / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write_file(root / "other" / "junit.xml", "<testsuites/>\n");
  write_file(root / "other" / "notes.raw", "1 2 3\n");
  fs::create_directory_symlink(root / "other", root / "suite" / "linked");
  fs::create_directory_symlink(root / "suite", root / "suite" / "loop");  // a cycle
  const std::vector<std::string> files = find_scene_files((root / "suite").string());
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(fs::path(files[0]).filename(), "long_thin.json");
  EXPECT_EQ(fs::path(files[1]).filename(), "tri.obj");
}

TEST_F(PlanConformance, UnwritableOutputIsAnInputErrorBeforeAnyWork) {
  const fs::path root = test_root() / "plan";
  fs::create_directories(root);
  write_file(root / "a_file", "not a folder");
  ConformanceOptions o;
  o.suite_dir = (root / "no_suite_here").string();  // would fail later: the folder is checked first
  o.out_dir = (root / "a_file" / "out").string();
  try {
    plan_conformance(o);
    FAIL() << "an output folder below a file was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), o.out_dir);
  }
}

TEST_F(PlanConformance, SuiteProblemsAreInputErrors) {
  const fs::path root = test_root() / "plan_suite";
  fs::remove_all(root);
  ConformanceOptions o;
  o.out_dir = (root / "out").string();
  o.suite_dir = (root / "missing").string();
  EXPECT_THROW(plan_conformance(o), InputError);
  write_file(root / "dup/one.json", R"({"name": "x.same", "draws": [{"positions": [[0,0,0],[1,0,0],[0,1,0]]}]})");
  write_file(root / "dup/two.json", R"({"name": "x.same", "draws": [{"positions": [[0,0,0],[1,0,0],[0,1,0]]}]})");
  o.suite_dir = (root / "dup").string();
  EXPECT_THROW(plan_conformance(o), InputError);
  write_file(root / "glob/one.json", R"({"name": "x.one", "draws": [{"positions": [[0,0,0],[1,0,0],[0,1,0]]}]})");
  o.suite_dir = (root / "glob").string();
  o.case_globs = {"y.*"};
  EXPECT_THROW(plan_conformance(o), UsageError);
}

TEST_F(PlanConformance, TheBuiltInSuiteIsFoundNextToTheExecutable) {
  // This test binary's folder has a link to the source tree's scenes/ (tests/CMakeLists.txt), as
  // the rastercmp executable's has (app/CMakeLists.txt).
  EXPECT_EQ(fs::canonical(default_suite_dir()), fs::canonical(fs::path(RASTERCMP_SOURCE_DIR) / "scenes"));
  EXPECT_FALSE(find_scene_files(default_suite_dir()).empty());
  const auto candidates = suite_dir_candidates("/opt/x/bin/rastercmp");
  ASSERT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0], "/opt/x/bin/scenes");
  EXPECT_EQ(candidates[1], "/opt/x/share/rastercmp/scenes");
}

// The clean-up at the start of a run removes the temporaries ".STEM.tmpPID.EXT" a killed run left,
// only in the folders a run writes (--out, report/, report/cases/<case>/) and only where the writer
// is gone: a user's file of that shape deeper below --out, and a live process's temporary, stay.
TEST(ConformanceCleanup, StaleTemporariesOnlyInTheRunsFoldersAndOfDeadWriters) {
  const fs::path out = fs::temp_directory_path() / ("rastercmp_cleanup_" + std::to_string(getpid()));
  fs::remove_all(out);
  const std::string dead = "2147483000", live = std::to_string(getpid());
  const std::vector<fs::path> removed = {out / (".summary.tmp" + dead + ".json"),
                                         out / "report" / (".index.tmp" + dead + ".html"),
                                         out / "report" / "cases" / "t.a" / (".cpu.tmp" + dead + ".png")};
  const std::vector<fs::path> kept = {out / "notes" / (".draft.tmp" + dead + ".md"),
                                      out / "report" / "cases" / "t.a" / "deeper" / (".x.tmp" + dead + ".png"),
                                      out / (".results.tmp" + live + ".csv"), out / "summary.json"};
  for (const fs::path& p : removed) write_file(p, "half");
  for (const fs::path& p : kept) write_file(p, "keep");
  EXPECT_EQ(remove_stale_temporaries(out.string()), removed.size());
  for (const fs::path& p : removed) EXPECT_FALSE(fs::exists(p)) << p;
  for (const fs::path& p : kept) EXPECT_TRUE(fs::exists(p)) << p;
  fs::remove_all(out);
}

}  // namespace
}  // namespace rastercmp
