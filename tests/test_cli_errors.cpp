// Command-line errors of the built `rastercmp` executable (exit codes: model/errors.hpp):
// an output folder that cannot be written is exit 2 before any work, a bad or missing option is
// exit 2 and writes no file, and without a Vulkan driver the Vulkan commands exit 3 saying what to install.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <string>
#include <vector>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

const fs::path kGoodScene = kSourceDir / "scenes" / "fill" / "top_left" / "shared_edge.json";

// --- unwritable output --------------------------------------------------------------------

// A place no output folder can be made: below a regular file, in place of a regular file, and
// below /proc (where mkdir fails even for root, so this holds when the tests run as root).
std::vector<fs::path> unwritable_outputs(const TempDir& tmp) {
  const fs::path blocker = tmp / "blocker";
  write_file(blocker, "a file, not a folder\n");
  return {blocker, blocker / "out", "/proc/self/rastercmp_out"};
}

// Exit 2 with one error line naming the folder, stdout empty, the blocking file unchanged.
// Run without a Vulkan driver: exit 2 (not 3) shows the folder is checked before Vulkan starts.
void expect_unwritable(const std::vector<std::string>& args, const fs::path& out, const TempDir& tmp) {
  const TreeSnapshot before = snapshot_tree(tmp.path());
  const RunResult r = run_cli(args, kNoVulkanDriver);
  const std::string what = describe(args, r);
  EXPECT_EQ(r.signal, 0) << what;
  EXPECT_EQ(r.exit_code, 2) << what;
  EXPECT_EQ(r.out, "") << what;
  const std::vector<std::string> err = lines_of(r.err);
  ASSERT_EQ(err.size(), 1u) << what;
  EXPECT_NE(err[0].find(out.string()), std::string::npos) << "the folder is not named\n" << what;
  EXPECT_EQ(snapshot_tree(tmp.path()), before) << what;
}

TEST(CliErrors, RenderRejectsAnUnwritableOutputFolder) {
  const TempDir tmp;
  for (const fs::path& out : unwritable_outputs(tmp)) {
    for (const char* backend : {"cpu", "vulkan"}) {
      SCOPED_TRACE(std::string(backend) + " " + out.string());
      expect_unwritable({"render", kGoodScene.string(), "--backend", backend, "--out", out.string()}, out, tmp);
    }
  }
}

TEST(CliErrors, CompareRejectsAnUnwritableReportFolderOrJsonFile) {
  const TempDir tmp;
  for (const fs::path& out : unwritable_outputs(tmp)) {
    SCOPED_TRACE(out.string());
    expect_unwritable({"compare", kGoodScene.string(), "--report", out.string()}, out, tmp);
    expect_unwritable({"compare", kGoodScene.string(), "--json", (out / "compare.json").string()}, out, tmp);
  }
}

// A suite folder in tmp holding the one good scene.
fs::path one_scene_suite(const fs::path& tmp) {
  const fs::path suite = tmp / "suite";
  fs::create_directories(suite);
  fs::copy_file(kGoodScene, suite / "shared_edge.json");
  return suite;
}

TEST(CliErrors, ConformanceRejectsAnUnwritableOutputFolder) {
  const TempDir tmp;
  const fs::path suite = one_scene_suite(tmp.path());
  for (const fs::path& out : unwritable_outputs(tmp)) {
    SCOPED_TRACE(out.string());
    expect_unwritable({"conformance", "--suite", suite.string(), "--out", out.string()}, out, tmp);
  }
}

// A run into a folder that holds an earlier run's verdict removes it before it reads anything
// else, so that the new run, killed at any moment (even before its first write), never reads as
// the earlier run's pass. Shown with input the run then refuses (exit 2): the old verdict is gone.
TEST(CliErrors, ConformanceRemovesAnEarlierVerdictBeforeItReadsTheSuite) {
  const TempDir tmp;
  const fs::path out = tmp / "out";
  fs::create_directories(out);
  for (const char* name : {"summary.json", "results.csv", "failures.csv", "junit.xml"})
    write_file(out / name, std::string(name) == "summary.json" ? "{\"complete\": true, \"passed\": true}\n" : "");
  const std::vector<std::string> args = {"conformance", "--suite", (tmp / "none").string(), "--out", out.string()};
  const RunResult r = run_cli(args, kNoVulkanDriver);
  EXPECT_EQ(r.exit_code, 2) << describe(args, r);
  for (const char* name : {"summary.json", "results.csv", "failures.csv", "junit.xml"})
    EXPECT_FALSE(fs::exists(out / name)) << name;
}

TEST(CliErrors, CaptureRejectsAnUnwritableOutputFolder) {
  const TempDir tmp;
  const fs::path suite = one_scene_suite(tmp.path());
  for (const fs::path& out : unwritable_outputs(tmp)) {
    SCOPED_TRACE(out.string());
    expect_unwritable({"capture", "--suite", suite.string(), "--out", out.string()}, out, tmp);
  }
}

// --- bad command lines ----------------------------------------------------------------------

TEST(CliErrors, BadOrMissingOptionsExitTwoAndWriteNothing) {
  const TempDir tmp;
  const std::string scene = kGoodScene.string();
  const std::string out = (tmp / "out").string();  // no file may be written there
  const std::vector<std::vector<std::string>> command_lines = {
      {},                                                                 // no command
      {"frobnicate"},                                                     // unknown command
      {"render", scene, "--out", out, "--bogus"},                         // unknown option
      {"render", scene},                                                  // missing --out
      {"render", "--backend", "cpu", "--out", out},                       // missing scene
      {"render", scene, "--out", out, "--threads"},                       // option without its value
      {"render", scene, "--out", out, "--threads", "many"},               // not a number
      {"render", scene, "--out", out, "--backend", "opengl"},             // not a backend
      {"render", scene, "--out", out, "--profile", "exact"},              // not a profile
      {"render", scene, "--out", out, "--method", "fill"},                // not STAGE=NAME
      {"render", (tmp / "missing.json").string(), "--out", out},          // no such scene file
      {"compare"},                                                        // no scene
      {"compare", scene, "--bogus"},                                      // unknown option
      {"explain", scene},                                                 // missing --pixel
      {"explain", scene, "--pixel", "x,y"},                               // not a pixel
      {"explain", scene, "--pixel", "64,0"},                              // outside the 64x64 framebuffer
      {"conformance", "--out", out, "--case"},                            // option without its value
      {"conformance", "--out", out, "--shard", "3/2"},                    // shard index beyond the count
      {"conformance", "--out", out, "--jobs", "1073741824"},              // was SIGFPE (4 x jobs wrapped to 0)
      {"conformance", "--out", out, "--jobs", "257"},                     // past kMaxConformanceJobs
      {"conformance", "--out", out, "--baseline", "/dev/zero"},           // never ends (grew to 24 GB)
      {"conformance", "--out", out, "--skips", "/dev/stdin"},             // not a regular file
      {"conformance", "--out", out, "--suite", (tmp / "none").string()},  // no such suite
      {"merge"},                                                          // nothing to merge
      {"bench", "--scene", "suite", "--suite", (tmp / "none").string()},  // no such suite (was exit 4)
      {"bench", "--tasks", "16"},                                         // --tasks without --scaling --model
      {"bench", "--scaling", "--model", "--tasks", "3"},                  // not a worker count the model projects
  };
  for (const std::vector<std::string>& args : command_lines) {
    const RunResult r = run_cli(args, kNoVulkanDriver);
    const std::string what = describe(args, r);
    EXPECT_EQ(r.signal, 0) << what;
    EXPECT_EQ(r.exit_code, 2) << what;
    EXPECT_NE(r.err, "") << "no error message\n" << what;
    EXPECT_TRUE(files_of(snapshot_tree(tmp / "out")).empty()) << "an output file was written\n" << what;
    fs::remove_all(tmp / "out");  // each command line is judged on its own
  }
}

TEST(CliErrors, HelpExitsZero) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"--help"}, {"render", "--help"}, {"conformance", "--help"}}) {
    const RunResult r = run_cli(args);
    EXPECT_EQ(r.exit_code, 0) << describe(args, r);
    EXPECT_NE(r.out.find("--"), std::string::npos) << describe(args, r);
  }
}

// `methods` lists every stage and name (the registry, cpu_raster/classic/method_registry.hpp); --help
// names them too; a method that cannot run on the scene exits 2 naming the scene's feature.
TEST(CliErrors, MethodsAreListedAndAMethodTheSceneDoesNotSuitExitsTwo) {
  const RunResult listed = run_cli({"methods"});
  EXPECT_EQ(listed.exit_code, 0) << listed.err;
  for (const char* line : {"  cyrus_beck ", "  weiler_atherton ", "  flood ", "  pseudo_depth_7500 ",
                           "one depth step at far 7500 is 34.2 eye units in D16", "Flood Fill"})
    EXPECT_NE(listed.out.find(line), std::string::npos) << line << "\n" << listed.out;
  const RunResult json = run_cli({"methods", "--json"});
  EXPECT_EQ(json.exit_code, 0);
  EXPECT_NE(json.out.find("\"notes_section\": \"Cyrus-Beck Algorithm\""), std::string::npos) << json.out;
  const RunResult help = run_cli({"render", "--help"});
  EXPECT_NE(help.out.find("fill=exact, scanline, even_odd, winding, float_edge, flood"), std::string::npos) << help.out;
  const TempDir tmp;
  const std::vector<std::string> args{"render", kGoodScene.string(),  "--backend", "cpu",
                                      "--out",  (tmp / "o").string(), "--method",  "depth=pseudo_depth_75"};
  const RunResult refused = run_cli(args);
  EXPECT_EQ(refused.exit_code, 2) << describe(args, refused);
  EXPECT_NE(refused.err.find("$.draws[0].positions[0] has w = 1"), std::string::npos) << describe(args, refused);
}

// --- no Vulkan driver -----------------------------------------------------------------------

// Exit 3 and one line that says which Debian packages to install.
void expect_no_vulkan(const std::vector<std::string>& args, const EnvEdits& env = kNoVulkanDriver) {
  const RunResult r = run_cli(args, env);
  const std::string what = describe(args, r);
  EXPECT_EQ(r.signal, 0) << what;
  EXPECT_EQ(r.exit_code, 3) << what;
  const std::vector<std::string> err = lines_of(r.err);
  ASSERT_EQ(err.size(), 1u) << what;
  EXPECT_NE(err[0].find("apt-get install"), std::string::npos) << what;
  EXPECT_NE(err[0].find("mesa-vulkan-drivers"), std::string::npos) << what;
}

TEST(CliErrors, WithoutAVulkanDriverTheVulkanCommandsExitThree) {
  const TempDir tmp;
  expect_no_vulkan({"devices"});
  expect_no_vulkan({"devices", "--json"});
  expect_no_vulkan({"render", kGoodScene.string(), "--backend", "vulkan", "--out", (tmp / "vk").string()});
  EXPECT_TRUE(files_of(snapshot_tree(tmp / "vk")).empty()) << "render wrote files without a device";
  expect_no_vulkan({"compare", kGoodScene.string()});
  expect_no_vulkan({"capture", "--suite", kGoodScene.parent_path().string(), "--out", (tmp / "cap").string()});
  EXPECT_TRUE(files_of(snapshot_tree(tmp / "cap")).empty()) << "capture wrote files without a device";
}

TEST(CliErrors, WithoutAVulkanDriverTheCpuRendererStillWorks) {
  const TempDir tmp;
  const std::vector<std::string> args = {"render", kGoodScene.string(),   "--backend", "cpu",
                                         "--out",  (tmp / "cpu").string()};
  const RunResult r = run_cli(args, kNoVulkanDriver);
  ASSERT_EQ(r.exit_code, 0) << describe(args, r);
  EXPECT_TRUE(fs::is_regular_file(tmp / "cpu" / "owner.tif"));
  EXPECT_TRUE(fs::is_regular_file(tmp / "cpu" / "render.json"));
}

// --- issue #22: bad input that used to get through -------------------------------------------

// Exit 2, nothing on stdout, one error line holding every one of `needles`, no file under `tmp`
// written and no folder left behind. Run without the Vulkan loader: exit 2 (not 3) shows the
// input is refused before any Vulkan work.
void expect_refused(const std::vector<std::string>& args, const std::vector<std::string>& needles, const TempDir& tmp) {
  const TreeSnapshot before = snapshot_tree(tmp.path());
  const RunResult r = run_cli(args, kNoVulkanLoader);
  const std::string what = describe(args, r);
  EXPECT_EQ(r.signal, 0) << what;
  EXPECT_EQ(r.exit_code, 2) << what;
  EXPECT_EQ(r.out, "") << what;
  const std::vector<std::string> err = lines_of(r.err);
  ASSERT_EQ(err.size(), 1u) << what;
  for (const std::string& needle : needles) EXPECT_NE(err[0].find(needle), std::string::npos) << needle << "\n" << what;
  EXPECT_EQ(snapshot_tree(tmp.path()), before) << "something was written or left behind\n" << what;
}

TEST(CliErrors, AnUnknownMethodOnTheCommandLineIsRefusedWithTheAcceptedNames) {
  const TempDir tmp;
  const std::string out = (tmp / "out").string();
  const std::vector<std::string> fill = {"--method fill=nosuch",
                                         "known: exact, scanline, even_odd, winding, float_edge, flood"};
  const std::vector<std::string> stage = {"--method nosuch=x",
                                          "known stages: clip, cull, fill, line, depth, visibility, snap, tie_break"};
  for (const char* backend : {"cpu", "vulkan"}) {
    expect_refused({"render", kGoodScene.string(), "--backend", backend, "--out", out, "--method", "fill=nosuch"}, fill,
                   tmp);
  }
  expect_refused({"render", kGoodScene.string(), "--out", out, "--method", "nosuch=x"}, stage, tmp);
  expect_refused({"compare", kGoodScene.string(), "--method", "fill=nosuch", "--json", (tmp / "c.json").string()}, fill,
                 tmp);
  expect_refused({"conformance", "--out", out, "--method", "fill=nosuch"}, fill, tmp);
  // A long value is cut in the message, with its size.
  const RunResult r =
      run_cli({"render", kGoodScene.string(), "--out", out, "--method", "fill=" + std::string(100000, 'x')});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_LT(r.err.size(), 200u);
  EXPECT_NE(r.err.find("xxx... (100005 bytes): expected STAGE=NAME"), std::string::npos) << r.err.substr(0, 200);
}

TEST(CliErrors, AnUnknownMethodInASceneIsRefusedWithFileAndJsonPath) {
  const TempDir tmp;
  std::string text = read_file(kGoodScene);
  const size_t brace = text.find('{');
  ASSERT_NE(brace, std::string::npos);
  text.insert(brace + 1, "\"methods\": {\"fill\": \"nosuch\"},");
  const fs::path suite = tmp / "suite";
  fs::create_directories(suite);
  const fs::path scene = suite / "bad_method.json";
  write_file(scene, text);
  const std::vector<std::string> needles = {scene.string() + ": $.methods.fill: ",
                                            "known: exact, scanline, even_odd, winding, float_edge, flood"};
  const std::string out = (tmp / "out").string();
  for (const char* backend : {"cpu", "vulkan"}) {
    expect_refused({"render", scene.string(), "--backend", backend, "--out", out}, needles, tmp);
  }
  expect_refused({"compare", kGoodScene.string(), scene.string(), "--report", (tmp / "report").string()}, needles, tmp);
  // conformance: its --out folder handling belongs to the runner; only the verdict is checked here.
  const std::vector<std::string> args = {"conformance", "--suite", suite.string(), "--out", out};
  const RunResult r = run_cli(args, kNoVulkanLoader);
  EXPECT_EQ(r.exit_code, 2) << describe(args, r);
  for (const std::string& needle : needles) EXPECT_NE(r.err.find(needle), std::string::npos) << describe(args, r);
}

// CLI11 refuses it while parsing (its message, naming the bound, and a --help hint).
TEST(CliErrors, ThreadsAreBounded) {
  const TempDir tmp;
  for (const char* threads : {"257", "400", "-1"}) {
    const std::vector<std::string> args = {"render", kGoodScene.string(), "--out", (tmp / "out").string(), "--threads",
                                           threads};
    const RunResult r = run_cli(args, kNoVulkanLoader);
    EXPECT_EQ(r.exit_code, 2) << describe(args, r);
    // CLI11 2.3 writes the range "0 to 256", 2.4 "[0 - 256]".
    EXPECT_NE(r.err.find(std::string("--threads: Value ") + threads + " not in range"), std::string::npos)
        << describe(args, r);
    EXPECT_NE(r.err.find("256"), std::string::npos) << describe(args, r);
    EXPECT_FALSE(fs::exists(tmp / "out"));
  }
}

// Threads the system refuses (here an address-space limit too small for 255 thread stacks, which
// the child inherits) are exit 3 naming the count, not std::terminate (exit 134), and no output
// is left. ASan reserves terabytes of shadow: no address-space limit under it.
TEST(CliErrors, ThreadsTheSystemRefusesAreExitThree) {
#ifdef RASTERCMP_SANITIZER_BUILD
  GTEST_SKIP() << "an address-space limit cannot hold under ASan";
#else
  const TempDir tmp;
  // 512x512 pixels: enough work that the fast path starts every thread asked for.
  write_file(
      tmp / "big.json",
      R"({"width": 512, "height": 512, "draws": [{"positions": [[-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [0, 0.5, 0.5]]}]})");
  const std::vector<std::string> args = {"render", (tmp / "big.json").string(), "--threads", "256",
                                         "--out",  (tmp / "out").string()};
  rlimit as{}, stack{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &as), 0);
  ASSERT_EQ(getrlimit(RLIMIT_STACK, &stack), 0);
  rlimit small_as = as, small_stack = stack;
  small_as.rlim_cur = rlim_t(1) << 30;     // 1 GiB: the executable starts, 255 stacks of 8 MiB do not fit
  small_stack.rlim_cur = rlim_t(8) << 20;  // the thread stack size glibc takes from it
  ASSERT_EQ(setrlimit(RLIMIT_STACK, &small_stack), 0);
  ASSERT_EQ(setrlimit(RLIMIT_AS, &small_as), 0);
  const RunResult r = run_cli(args, kNoVulkanLoader);
  setrlimit(RLIMIT_AS, &as);
  setrlimit(RLIMIT_STACK, &stack);
  EXPECT_EQ(r.signal, 0) << describe(args, r);
  EXPECT_EQ(r.exit_code, 3) << describe(args, r);
  EXPECT_NE(r.err.find("cannot start 255 CPU worker threads"), std::string::npos) << describe(args, r);
  EXPECT_FALSE(fs::exists(tmp / "out"));
#endif
}

TEST(CliErrors, ScenesOverTheSizeLimitAreRefused) {
  const TempDir tmp;
  expect_refused({"render", "/dev/zero", "--out", (tmp / "out").string()},
                 {"/dev/zero: $: expected a scene file of at most 64 MiB"}, tmp);
}

TEST(CliErrors, OutputFilesAreCheckedBeforeAnyWork) {
  const TempDir tmp;
  fs::create_directories(tmp / "existing");
  const std::vector<std::string> needles = {(tmp / "existing").string(), "expected a file to write"};
  expect_refused({"compare", kGoodScene.string(), "--json", (tmp / "existing").string()}, needles, tmp);
  expect_refused({"bench", "--scene", "perspective", "--json", (tmp / "existing").string()}, needles, tmp);
  expect_refused({"reduce", kGoodScene.string(), "--out", (tmp / "existing").string()}, needles, tmp);
  // A --json file in a folder not yet made: refused for another reason (here no Vulkan) and the
  // folder made for it is removed again.
  const std::vector<std::string> args = {"compare", kGoodScene.string(), "--json", (tmp / "new" / "c.json").string()};
  EXPECT_EQ(run_cli(args, kNoVulkanLoader).exit_code, 3);
  EXPECT_FALSE(fs::exists(tmp / "new"));
}

TEST(CliErrors, VersionPrintsTheProjectVersion) {
  const RunResult r = run_cli({"--version"});
  EXPECT_EQ(r.exit_code, 0) << describe({"--version"}, r);
  EXPECT_EQ(r.out, std::string("rastercmp ") + RASTERCMP_VERSION + "\n");
}

// --- no Vulkan loader at all ------------------------------------------------------------------

// The executable opens libvulkan.so.1 at run time: without it the CPU path works and every Vulkan
// command is exit 3 with the hint (not 127 from the dynamic linker), leaving no output behind.
TEST(CliErrors, WithoutTheVulkanLoaderCpuWorksAndVulkanCommandsExitThree) {
  const TempDir tmp;
  const std::vector<std::string> cpu = {"render", kGoodScene.string(),   "--backend", "cpu",
                                        "--out",  (tmp / "cpu").string()};
  const RunResult r = run_cli(cpu, kNoVulkanLoader);
  ASSERT_EQ(r.exit_code, 0) << describe(cpu, r);
  EXPECT_TRUE(fs::is_regular_file(tmp / "cpu" / "owner.tif"));

  const std::vector<std::vector<std::string>> vulkan = {
      {"devices"},
      {"render", kGoodScene.string(), "--backend", "vulkan", "--out", (tmp / "vk").string()},
      {"compare", kGoodScene.string()},
      {"compare", kGoodScene.string(), "--json", (tmp / "compare.json").string()},
  };
  for (const std::vector<std::string>& args : vulkan) {
    const RunResult v = run_cli(args, kNoVulkanLoader);
    expect_no_vulkan(args, kNoVulkanLoader);
    EXPECT_NE(v.err.find("/nonexistent/libvulkan.so.1"), std::string::npos) << "the loader is not named\n"
                                                                            << describe(args, v);
  }
  EXPECT_FALSE(fs::exists(tmp / "vk")) << "render left an output folder";
  EXPECT_FALSE(fs::exists(tmp / "compare.json"));

  const fs::path suite = tmp / "suite";
  fs::create_directories(suite);
  fs::copy_file(kGoodScene, suite / "shared_edge.json");
  expect_no_vulkan({"conformance", "--suite", suite.string(), "--out", (tmp / "conf").string()}, kNoVulkanLoader);
}

}  // namespace
}  // namespace rastercmp::cli_test

// soak and reduce (docs/soak.md): an unknown family, a zero or missing budget, --every-worker
// without the fast path's workers and a missing scene are bad input (exit 2) with a message that
// names the problem, before any device work.
TEST(CliErrors, SoakAndReduceRejectBadInput) {
  using namespace rastercmp::cli_test;
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases{
      {{"soak", "--count", "10", "--family", "no_such_family"}, "unknown family"},
      {{"soak", "--count", "0"}, "--count"},
      {{"soak", "--count", "ten"}, "--count"},
      {{"soak", "--count", "10", "--seed", "18446744073709551616"},
       "expected an integer from 0 to 18446744073709551615, found 18446744073709551616"},
      {{"soak", "--count", "10", "--seed", "-1"}, "--seed"},
      {{"soak"}, "--count"},
      {{"soak", "--count", "10", "--every-worker"}, "--every-worker: needs --threads 2 or more"},
      {{"soak", "--count", "10", "--every-worker", "--threads", "1"}, "--every-worker: needs --threads 2 or more"},
      {{"reduce", "/nonexistent/rastercmp_no_scene.json"}, "rastercmp_no_scene.json"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << describe(c.args, r);
    EXPECT_NE(r.err.find(c.message), std::string::npos) << describe(c.args, r);
  }
}
