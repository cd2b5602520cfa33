// Captures as an input (docs/compare.md "Captures"): `rastercmp capture` records a small suite on
// lavapipe, and `conformance --captures` / `compare --capture` judge the recorded renders with the
// verdicts and outputs of a live run. Captures that do not fit their scene (a missing or corrupt
// file, another size, sample count or depth format) are that case's ResourceError naming the file,
// and a render.json without the device's limits (as older captures) still judges.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <fstream>
#include <map>

#include <string>
#include <vector>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

// Depth formats, MSAA with lines, a fractional viewport, a scene the device refuses nothing of
// and one the CPU profiles cannot judge (point_list: NotSupported).
const std::vector<std::string> kScenes = {
    "depth/format/d16_unorm.json", "msaa/lines/mixed_modes.json",   "viewport/offset/fractional.json",
    "clip/all_planes.json",        "not_supported/point_list.json",
};

// A suite folder holding copies of kScenes, laid out as in scenes/.
fs::path make_suite(const TempDir& tmp) {
  const fs::path suite = tmp / "suite";
  for (const std::string& scene : kScenes) {
    fs::create_directories((suite / scene).parent_path());
    fs::copy_file(kSourceDir / "scenes" / scene, suite / scene);
  }
  return suite;
}

RunResult run_ok(const std::vector<std::string>& args, int expected_exit = 0, const EnvEdits& env = {}) {
  const RunResult r = run_cli(args, env);
  EXPECT_EQ(r.exit_code, expected_exit) << describe(args, r);
  return r;
}

// summary.json has no durations: two runs that judge alike write the same bytes. Judging captures
// needs no Vulkan driver, so those runs go without one.
std::string conformance_summary(const fs::path& suite, const fs::path& out, const std::string& profile,
                                const std::string& captures) {
  std::vector<std::string> args = {"conformance", "--suite",   suite.string(), "--out",
                                   out.string(),  "--profile", profile};
  if (!captures.empty()) args.insert(args.end(), {"--captures", captures});
  run_ok(args, 0, captures.empty() ? EnvEdits{} : kNoVulkanDriver);
  return read_file(out / "summary.json");
}

// Every file below `dir`, relative path -> bytes.
std::map<std::string, std::string> contents_below(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return files;
}

// A full disk in the middle of a scene's files: exit 2 naming the file it could not write, and the
// scene's folder is the earlier capture byte for byte, with no temporary beside it (it used to hold
// new images beside the earlier render.json). The disk fills at the scene's first, third or last
// file (RASTERCMP_TEST_WRITE_FAULT, model/image_io.cpp): a file-size limit (ulimit -f) would stop
// lavapipe first from Mesa 25 on, whose device memory lives in memory files the limit applies to.
TEST(CliCapture, AFullDiskLeavesEachScenesFolderAsItWas) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const fs::path suite = tmp / "suite", out = tmp / "out";
  fs::create_directories(suite);
  const std::string head = R"({"name": "t.big", "width": 256, "height": 256, "depth_format": "d32_sfloat",
    "draws": [{"positions": [[-0.9, -0.9, 0.2], [0.9, -0.8, 0.6], )";
  write_file(suite / "big.json", head + R"([-0.1, 0.9, 0.9]]}]})");
  run_ok({"capture", "--suite", suite.string(), "--out", out.string()});
  const std::map<std::string, std::string> earlier = contents_below(out / "big");
  ASSERT_TRUE(earlier.count("render.json") && earlier.count("depth_raw.tif"));
  write_file(suite / "big.json", head + R"([-0.1, 0.5, 0.4]]}]})");  // other images now
  for (const int full_at : {1, 3, 5}) {  // a scene writes five files
    const std::string command = "RASTERCMP_TEST_WRITE_FAULT=" + std::to_string(full_at) + " exec " +
                                kBinary.string() + " capture --suite " + suite.string() + " --out " + out.string() +
                                " >" + (tmp / "log").string() + " 2>&1";
    const int status = std::system(("sh -c \"" + command + "\"").c_str());
    ASSERT_TRUE(WIFEXITED(status)) << command;
    const std::string log = read_file(tmp / "log");
    EXPECT_EQ(WEXITSTATUS(status), 2) << command << "\n" << log;
    EXPECT_NE(log.find("could not write"), std::string::npos) << log;
    EXPECT_EQ(contents_below(out / "big"), earlier) << "a full disk at file " << full_at << " left another capture\n"
                                                    << log;
    for (const auto& e : fs::directory_iterator(out))
      EXPECT_TRUE(e.path().filename() == "big" || e.path().filename() == ".rastercmp.lock") << e.path();
  }
  // Without the limit the new capture replaces the earlier one whole, and removes the temporary
  // folder a killed capture left (pid 2147483647: no such process).
  fs::create_directories(out / ".big.tmp2147483647");
  write_file(out / ".big.tmp2147483647" / "owner.tif", "half");
  run_ok({"capture", "--suite", suite.string(), "--out", out.string()});
  EXPECT_FALSE(fs::exists(out / ".big.tmp2147483647"));
  EXPECT_NE(contents_below(out / "big").at("depth_raw.tif"), earlier.at("depth_raw.tif"));
}

// capture takes the --out lock as conformance does: a folder another run is writing is exit 2
// naming its pid, and nothing is recorded there.
TEST(CliCapture, ACaptureIntoALockedFolderExits2NamingTheHolder) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const fs::path suite = make_suite(tmp);
  const fs::path captures = tmp / "captures";
  HeldOutputLock lock(captures);
  const RunResult r = run_ok({"capture", "--suite", suite.string(), "--out", captures.string()}, 2);
  lock.release();
  EXPECT_NE(r.err.find("pid 31337"), std::string::npos) << r.err;
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(captures)) ++entries;
  EXPECT_EQ(entries, 1u);  // the lock file alone
}

TEST(CliCapture, CapturedSuiteJudgesLikeALiveRun) {
  const TempDir tmp;
  const fs::path suite = make_suite(tmp);
  const fs::path captures = tmp / "captures";
  run_ok({"capture", "--suite", suite.string(), "--out", captures.string()});
  // One folder per scene, as the suite lays them out, with the device's limits recorded.
  const std::string meta = read_file(captures / "viewport" / "offset" / "fractional" / "render.json");
  for (const char* key : {"\"limits\"", "\"subPixelPrecisionBits\": 8", "\"viewportSubPixelBits\"", "\"strictLines\"",
                          "\"standardSampleLocations\"", "\"lineWidthRange\"", "\"device_name\"", "\"driver\""})
    EXPECT_NE(meta.find(key), std::string::npos) << key << " missing from\n" << meta;
  EXPECT_TRUE(fs::exists(captures / "msaa" / "lines" / "mixed_modes" / "owner.tif"));

  for (const std::string profile : {"lavapipe", "spec"}) {
    SCOPED_TRACE(profile);
    const std::string live = conformance_summary(suite, tmp / ("live_" + profile), profile, "");
    const std::string judged = conformance_summary(suite, tmp / ("judged_" + profile), profile, captures.string());
    EXPECT_EQ(judged, live);
    EXPECT_NE(live.find("NotSupported"), std::string::npos);  // point_list, so the run is not all Pass
  }
  // A classic CPU method judged against the captured device render: the flood fill's outline adds
  // samples, and the verdict and every sample line name them from the method's side.
  const RunResult m = run_ok({"compare", (suite / "depth" / "format" / "d16_unorm.json").string(), "--capture",
                              (captures / "depth" / "format" / "d16_unorm").string(), "--method", "fill=flood"},
                             1, kNoVulkanDriver);
  EXPECT_NE(m.out.find("Fail (0 the method lacks, "), std::string::npos) << m.out;
  EXPECT_NE(m.out.find(": the method adds: device background, method draw "), std::string::npos) << m.out;
  EXPECT_EQ(m.out.find(": missing: "), std::string::npos) << m.out;
}

TEST(CliCapture, BrokenCapturesAreResourceErrorsNamingTheFile) {
  const TempDir tmp;
  const fs::path suite = make_suite(tmp);
  const fs::path captures = tmp / "captures";
  run_ok({"capture", "--suite", suite.string(), "--out", captures.string()});

  const fs::path corrupt = captures / "depth" / "format" / "d16_unorm" / "owner.tif";
  write_file(corrupt, "II*\0 not a TIFF any more");
  const fs::path missing = captures / "clip" / "all_planes" / "depth_raw.tif";
  fs::remove(missing);
  // Another size: render.json and owner.tif both of a 16x16 render, the scene is not.
  const fs::path resized_dir = captures / "viewport" / "offset" / "fractional";
  run_ok({"render", (kSourceDir / "scenes" / "fill" / "top_left" / "shared_edge.json").string(), "--backend", "vulkan",
          "--out", resized_dir.string()});
  // No limits in render.json (as `render` wrote it before, and older captures): still judged.
  const fs::path old_meta = captures / "msaa" / "lines" / "mixed_modes" / "render.json";
  std::string text = read_file(old_meta);
  const size_t limits = text.find(",\n  \"device_name\"");
  ASSERT_NE(limits, std::string::npos) << text;
  write_file(old_meta, text.substr(0, limits) + "\n}\n");

  const fs::path out = tmp / "out";
  const RunResult r = run_ok({"conformance", "--suite", suite.string(), "--out", out.string(), "--profile", "spec",
                              "--captures", captures.string()},
                             1);
  const std::string summary = read_file(out / "summary.json");
  const std::string failures = read_file(out / "failures.csv");
  // deqp-runner's status of a ResourceError is Fail; summary.json keeps the verdict.
  for (const char* name :
       {"rastercmp.depth.format.d16_unorm", "rastercmp.clip.all_planes", "rastercmp.viewport.offset.fractional"}) {
    EXPECT_NE(failures.find(std::string(name) + ",Fail"), std::string::npos) << failures;
    const size_t at = summary.find(std::string("\"scene\": \"") + name + "\"");
    ASSERT_NE(at, std::string::npos) << name;
    EXPECT_LT(summary.find("\"verdict\": \"ResourceError\"", at), summary.find("\"scene\": ", at + 1)) << name;
  }
  EXPECT_EQ(failures.find("mixed_modes"), std::string::npos) << failures;
  for (const fs::path& file : {corrupt, missing, resized_dir / "owner.tif"})
    EXPECT_NE(summary.find(file.string()), std::string::npos) << file << " not named in\n" << summary;

  // compare --capture: the same verdict and file for one scene, and exit 1.
  const RunResult c = run_ok({"compare", (suite / "clip" / "all_planes.json").string(), "--profile", "spec",
                              "--capture", missing.parent_path().string()},
                             1);
  EXPECT_NE(c.out.find("ResourceError"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find(missing.string()), std::string::npos) << c.out;
  // A render.json with impossible limits: the case's ResourceError too, naming render.json.
  const fs::path bad_limits = captures / "msaa" / "lines" / "mixed_modes" / "render.json";
  write_file(bad_limits, "{\"backend\": \"vulkan\", \"limits\": {\"subPixelPrecisionBits\": 0}}\n");
  const RunResult l = run_ok({"compare", (suite / "msaa" / "lines" / "mixed_modes.json").string(), "--profile", "spec",
                              "--capture", bad_limits.parent_path().string()},
                             1);
  EXPECT_NE(l.out.find("ResourceError"), std::string::npos) << l.out;
  EXPECT_NE(l.out.find(bad_limits.string() + ": $.limits.subPixelPrecisionBits"), std::string::npos) << l.out;
  // A negative size is refused, not wrapped to 4294967248.
  write_file(bad_limits, "{\"backend\": \"vulkan\", \"width\": -48, \"height\": 32, \"samples\": 1}\n");
  const RunResult w = run_ok({"compare", (suite / "msaa" / "lines" / "mixed_modes.json").string(), "--profile", "spec",
                              "--capture", bad_limits.parent_path().string()},
                             1);
  EXPECT_NE(w.out.find(bad_limits.string() + ": $.width: expected an integer from 0 to 16384, found -48"),
            std::string::npos)
      << w.out;
  // Tampered captures never hang or swallow the machine: a FIFO named render.json, an owner.tif
  // that links to /dev/zero, and a sparse 2 GiB owner.tif for a small render are each refused,
  // naming the file, before anything reads them.
  const fs::path dir = bad_limits.parent_path();
  write_file(bad_limits, "{\"backend\": \"vulkan\", \"width\": 16, \"height\": 16, \"samples\": 4}\n");
  fs::remove(dir / "owner.tif");
  fs::create_symlink("/dev/zero", dir / "owner.tif");
  const std::string scene_file = (suite / "msaa" / "lines" / "mixed_modes.json").string();
  const auto judged = [&] {
    return run_ok({"compare", scene_file, "--profile", "spec", "--capture", dir.string()}, 1);
  };
  const RunResult z = judged();
  EXPECT_NE(z.out.find("as a regular file, not a folder, pipe or device"), std::string::npos) << z.out;
  fs::remove(dir / "owner.tif");
  { std::ofstream(dir / "owner.tif") << "II*"; }
  fs::resize_file(dir / "owner.tif", uintmax_t(2) << 30);
  const RunResult sparse = judged();
  EXPECT_NE(sparse.out.find("found 2147483648 bytes"), std::string::npos) << sparse.out;
  fs::remove(bad_limits);
  ASSERT_EQ(mkfifo(bad_limits.c_str(), 0600), 0);
  const RunResult fifo = judged();
  EXPECT_NE(fifo.out.find("render.json: $: expected render.json as a regular file"), std::string::npos) << fifo.out;
  // A capture root with nothing in it is a usage error of the whole run (exit 2).
  const fs::path empty = tmp / "empty";
  fs::create_directories(empty);
  run_ok({"conformance", "--suite", suite.string(), "--out", (tmp / "out2").string(), "--captures", empty.string()}, 2);
}

// explain --capture: the NVIDIA H100 render of a coplanar triangle with other vertices, pushed back
// by 3 r (tests/test_spec_owners.cpp): at (20, 20) the device left the biased triangle, an owner
// an exact device with nearest rounding leaves there (docs/spec-profile.md "Owners"). No Vulkan
// driver needed; a folder without a capture is bad input.
TEST(CliCapture, ExplainJudgesACaptureAndNamesTheOwnerAlternative) {
  const std::string scene = "depth/bias/x8_d24_unorm/constant";
  const std::string capture = (kSourceDir / "tests" / "data" / "captures" / "nvidia-h100" / scene).string();
  const std::vector<std::string> args = {"explain",   (kSourceDir / "scenes" / (scene + ".json")).string(),
                                         "--pixel",   "20,20",
                                         "--profile", "spec",
                                         "--capture", capture};
  const RunResult r = run_ok(args, 0, kNoVulkanDriver);
  EXPECT_NE(r.out.find("  estimate:     draw 0 primitive 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  alternatives: draw 1 primitive 0 (id 0x01000000): a device with nearest vertex rounding"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("  observed:     draw 1 primitive 0 (id 0x01000000): an allowed alternative (Pass)"),
            std::string::npos)
      << r.out;
  const TempDir tmp;
  std::vector<std::string> no_capture = args;
  no_capture.back() = tmp.path().string();
  run_ok(no_capture, 2, kNoVulkanDriver);
}

}  // namespace
}  // namespace rastercmp::cli_test
