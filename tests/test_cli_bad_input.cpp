// The bad-scene catalogue (tests/data/bad_scenes/expected.tsv) through the commands that read
// scenes, run as the built `rastercmp` executable: exit 2 (model/errors.hpp kExitBadInput), one
// error line on stderr naming the file, the JSON path and what was expected, no crash, nothing
// on stdout, and no output file written (a pre-existing output folder is left as it was).
// The scene loader itself is tested in tests/test_scene_loader.cpp; this is the end-to-end part.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

const fs::path kBadDir = kSourceDir / "tests" / "data" / "bad_scenes";
// A valid scene put beside the bad one in a conformance suite: loading must stop the run anyway.
const fs::path kGoodScene = kSourceDir / "scenes" / "fill" / "top_left" / "shared_edge.json";

struct BadScene {
  std::string file;
  std::string json_path;
  std::string message;
};

std::vector<BadScene> read_manifest() {
  std::vector<BadScene> scenes;
  for (const std::string& line : lines_of(read_file(kBadDir / "expected.tsv"))) {
    if (line.empty() || line[0] == '#') continue;
    const size_t tab1 = line.find('\t'), tab2 = line.find('\t', tab1 + 1);
    if (tab1 == std::string::npos || tab2 == std::string::npos) throw std::runtime_error("bad manifest line: " + line);
    scenes.push_back({line.substr(0, tab1), line.substr(tab1 + 1, tab2 - tab1 - 1), line.substr(tab2 + 1)});
  }
  return scenes;
}

// What one command needs: its arguments for a scene path and an output folder, and the scene
// path the error message must name (conformance reads a copy inside a suite folder).
struct Invocation {
  std::vector<std::string> args;
  std::string scene_path;
};
using MakeInvocation = std::function<Invocation(const BadScene&, const TempDir&, const fs::path& out)>;

Invocation direct(std::vector<std::string> args, const fs::path& scene) { return {std::move(args), scene.string()}; }

Invocation render_cpu(const BadScene& bad, const TempDir&, const fs::path& out) {
  const fs::path scene = kBadDir / bad.file;
  return direct({"render", scene.string(), "--backend", "cpu", "--out", out.string()}, scene);
}

Invocation render_vulkan(const BadScene& bad, const TempDir&, const fs::path& out) {
  const fs::path scene = kBadDir / bad.file;
  return direct({"render", scene.string(), "--backend", "vulkan", "--out", out.string()}, scene);
}

// The good scene goes first on the command line: a bad scene later in the list must stop the
// command before it renders anything.
Invocation compare(const BadScene& bad, const TempDir&, const fs::path& out) {
  const fs::path scene = kBadDir / bad.file;
  return direct({"compare", kGoodScene.string(), scene.string(), "--json", (out / "compare.json").string(), "--report",
                 (out / "report").string()},
                scene);
}

Invocation explain(const BadScene& bad, const TempDir&, const fs::path&) {
  const fs::path scene = kBadDir / bad.file;
  return direct({"explain", scene.string(), "--pixel", "0,0"}, scene);
}

Invocation conformance(const BadScene& bad, const TempDir& tmp, const fs::path& out) {
  const fs::path suite = tmp / "suite";
  fs::create_directories(suite);
  fs::copy_file(kGoodScene, suite / "good.json");
  fs::copy_file(kBadDir / bad.file, suite / bad.file);
  return direct({"conformance", "--suite", suite.string(), "--out", out.string()}, (suite / bad.file).string());
}

// Runs `make` for the manifest entries offset, offset + stride, ... Every other run gets an
// --out folder that does not exist (it must still not exist after), the rest a folder holding a
// file (left unchanged). `folders_may_appear`: empty folders (no files) may be made under --out.
void check_catalogue(const MakeInvocation& make, size_t stride, size_t offset, bool folders_may_appear = false) {
  const std::vector<BadScene> catalogue = read_manifest();
  ASSERT_GE(catalogue.size(), 45u) << "the manifest lost its entries";
  size_t checked = 0;
  for (size_t i = offset; i < catalogue.size(); i += stride) {
    const BadScene& bad = catalogue[i];
    SCOPED_TRACE(bad.file);
    const TempDir tmp;
    const fs::path out = tmp / "out";
    if (checked % 2 == 1) {
      fs::create_directories(out);
      write_file(out / "keep.txt", "from an earlier run\n");
    }
    const TreeSnapshot before = snapshot_tree(out);
    const Invocation inv = make(bad, tmp, out);
    const RunResult r = run_cli(inv.args);
    const std::string what = describe(inv.args, r);

    EXPECT_EQ(r.signal, 0) << what;
    EXPECT_EQ(r.exit_code, 2) << what;
    EXPECT_EQ(r.out, "") << what;
    const std::vector<std::string> err = lines_of(r.err);
    ASSERT_EQ(err.size(), 1u) << "expected exactly one error line\n" << what;
    EXPECT_NE(err[0].find(inv.scene_path + ": "), std::string::npos) << "the file is not named\n" << what;
    EXPECT_NE(err[0].find(": " + bad.json_path + ": "), std::string::npos) << "the JSON path is not named\n" << what;
    EXPECT_NE(err[0].find(bad.message), std::string::npos) << "the message lacks \"" << bad.message << "\"\n" << what;

    const TreeSnapshot after = snapshot_tree(out);
    if (folders_may_appear)
      EXPECT_EQ(files_of(after), files_of(before)) << "an output file was written or changed\n" << what;
    else
      EXPECT_EQ(after, before) << "the output folder was created or changed\n" << what;
    ++checked;
  }
  EXPECT_GT(checked, 0u);
}

// Every file goes through one command, the five commands taking turns (file i through command
// i % 5): the scene loader's answer for each file is tested in-process (test_scene_loader.cpp);
// what this adds is each command's handling of it (exit 2, one line, nothing written), and every
// process start costs ~0.4 s of CPU (the shared libraries OpenImageIO pulls in).
constexpr size_t kCommands = 5;

TEST(CliBadInput, RenderCpuRejectsBadScenes) { check_catalogue(render_cpu, kCommands, 0); }

// The scene is read before the Vulkan instance is made, so these never start the driver.
TEST(CliBadInput, RenderVulkanRejectsBadScenes) { check_catalogue(render_vulkan, kCommands, 1); }

TEST(CliBadInput, CompareRejectsBadScenes) { check_catalogue(compare, kCommands, 2); }

TEST(CliBadInput, ExplainRejectsBadScenes) { check_catalogue(explain, kCommands, 3); }

// conformance makes --out and --out/report (empty) before it reads the suite
// (compare/conformance.cpp plan_conformance); no file may be written there.
TEST(CliBadInput, ConformanceRejectsASuiteWithABadScene) { check_catalogue(conformance, kCommands, 4, true); }

}  // namespace
}  // namespace rastercmp::cli_test
