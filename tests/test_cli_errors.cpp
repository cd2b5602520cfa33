// Command-line errors of the built `rastercmp` executable (exit codes: model/errors.hpp):
// an output folder that cannot be written is exit 2 before any work, a bad or missing option is
// exit 2 and writes no file, and without a Vulkan driver the Vulkan commands exit 3 saying what to install.
#include <gtest/gtest.h>

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

TEST(CliErrors, ConformanceRejectsAnUnwritableOutputFolder) {
  const TempDir tmp;
  const fs::path suite = tmp / "suite";
  fs::create_directories(suite);
  fs::copy_file(kGoodScene, suite / "shared_edge.json");
  for (const fs::path& out : unwritable_outputs(tmp)) {
    SCOPED_TRACE(out.string());
    expect_unwritable({"conformance", "--suite", suite.string(), "--out", out.string()}, out, tmp);
  }
}

TEST(CliErrors, CaptureRejectsAnUnwritableOutputFolder) {
  const TempDir tmp;
  const fs::path suite = tmp / "suite";
  fs::create_directories(suite);
  fs::copy_file(kGoodScene, suite / "shared_edge.json");
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
      {"conformance", "--out", out, "--suite", (tmp / "none").string()},  // no such suite
      {"merge"},                                                          // nothing to merge
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

// --- no Vulkan driver -----------------------------------------------------------------------

// Exit 3 and one line that says which Debian packages to install.
void expect_no_vulkan(const std::vector<std::string>& args) {
  const RunResult r = run_cli(args, kNoVulkanDriver);
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

}  // namespace
}  // namespace rastercmp::cli_test

// soak and reduce (docs/soak.md): an unknown family, a zero or missing budget and a missing scene
// are bad input (exit 2) with a message that names the problem, before any device work.
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
      {{"soak"}, "--count"},
      {{"reduce", "/nonexistent/rastercmp_no_scene.json"}, "rastercmp_no_scene.json"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << describe(c.args, r);
    EXPECT_NE(r.err.find(c.message), std::string::npos) << describe(c.args, r);
  }
}
