// Determinism of the built `rastercmp` executable: the same command gives the same bytes.
// render (cpu with --threads 0, 1 and 2, vulkan twice) writes byte-identical owner.tif,
// depth_raw.tif, depth.exr, owner.png and render.json; conformance gives identical outputs
// across runs and --threads, durations aside (docs/compare.md "Conformance runs").
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

// Every depth format, MSAA, lines, clipping, bias, several draws, an odd framebuffer size.
const std::vector<std::string> kScenes = {
    "depth/format/d16_unorm.json",  "depth/format/x8_d24_unorm.json",
    "depth/format/none.json",       "depth/bias/d32_sfloat/slope.json",
    "msaa/depth/intersecting.json", "msaa/lines/mixed_modes.json",
    "clip/all_planes.json",         "multidraw/mixed_state.json",
    "viewport/odd_size.json",
};

// Renders `scene` into a new folder below `tmp` and returns what it wrote.
TreeSnapshot render(const TempDir& tmp, const std::string& scene, const std::vector<std::string>& extra) {
  static int run = 0;
  const fs::path out = tmp / ("run" + std::to_string(run++));
  std::vector<std::string> args = {"render", (kSourceDir / "scenes" / scene).string(), "--out", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult r = run_cli(args);
  EXPECT_EQ(r.exit_code, 0) << describe(args, r);
  return snapshot_tree(out);
}

void expect_render_outputs(const TreeSnapshot& files) {
  for (const char* name : {"owner.tif", "owner.png", "render.json"})
    EXPECT_EQ(files.count(name), 1u) << name << " missing";
  EXPECT_EQ(files.count("depth_raw.tif"), files.count("depth.exr"));
}

void expect_same_bytes(const TreeSnapshot& a, const TreeSnapshot& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (const auto& [name, bytes] : a) {
    ASSERT_EQ(b.count(name), 1u) << what << ": " << name << " only in the first run";
    EXPECT_TRUE(bytes == b.at(name)) << what << ": " << name << " differs";
  }
}

// render_cpu's --threads 1 and 2 (the fast path) are held bit-identical to --threads 0 (the
// exact path); render.json does not record the thread count, so every byte must agree.
TEST(CliDeterminism, CpuRenderIsByteIdenticalAcrossRunsAndThreadCounts) {
  const TempDir tmp;
  for (const std::string& scene : kScenes) {
    SCOPED_TRACE(scene);
    const TreeSnapshot first = render(tmp, scene, {"--backend", "cpu", "--threads", "0"});
    expect_render_outputs(first);
    expect_same_bytes(first, render(tmp, scene, {"--backend", "cpu", "--threads", "0"}), "second run");
    expect_same_bytes(first, render(tmp, scene, {"--backend", "cpu", "--threads", "1"}), "--threads 1");
    expect_same_bytes(first, render(tmp, scene, {"--backend", "cpu", "--threads", "2"}), "--threads 2");
  }
}

TEST(CliDeterminism, VulkanRenderIsByteIdenticalAcrossRuns) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  for (const std::string& scene : kScenes) {
    SCOPED_TRACE(scene);
    const TreeSnapshot first = render(tmp, scene, {"--backend", "vulkan"});
    expect_render_outputs(first);
    expect_same_bytes(first, render(tmp, scene, {"--backend", "vulkan"}), "second run");
  }
}

// --- conformance ----------------------------------------------------------------------------

// The outputs of a conformance run with the durations taken out: results.csv keeps
// `name,status`, junit.xml loses its time="..." attributes; every other file stays as written.
TreeSnapshot without_durations(TreeSnapshot files) {
  if (files.count("results.csv")) {
    std::string kept;
    for (const std::string& line : lines_of(files["results.csv"])) kept += line.substr(0, line.rfind(',')) + "\n";
    files["results.csv"] = kept;
  }
  if (files.count("junit.xml"))
    files["junit.xml"] = std::regex_replace(files["junit.xml"], std::regex(R"( time="[^"]*")"), "");
  return files;
}

TreeSnapshot conformance(const TempDir& tmp, const std::string& name, const std::string& threads) {
  const fs::path out = tmp / name;
  const std::vector<std::string> args = {
      "conformance", "--case",    "rastercmp.depth.format.*", "--case", "rastercmp.msaa.lines.*", "--threads", threads,
      "--out",       out.string()};
  const RunResult r = run_cli(args);
  EXPECT_EQ(r.signal, 0) << describe(args, r);
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << describe(args, r);
  return without_durations(files_of(snapshot_tree(out)));
}

TEST(CliDeterminism, ConformanceOutputsAreIdenticalAcrossRunsAndThreadCounts) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const TreeSnapshot first = conformance(tmp, "first", "1");
  for (const char* name : {"results.csv", "failures.csv", "junit.xml", "summary.json", "report/index.html"})
    EXPECT_EQ(first.count(name), 1u) << name << " missing";
  EXPECT_EQ(lines_of(first.at("results.csv")).size(), 7u) << first.at("results.csv");  // 4 + 3 cases
  expect_same_bytes(first, conformance(tmp, "second", "1"), "second run");
  expect_same_bytes(first, conformance(tmp, "threads2", "2"), "--threads 2");
}

}  // namespace
}  // namespace rastercmp::cli_test
