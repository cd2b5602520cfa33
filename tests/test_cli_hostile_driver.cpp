// `rastercmp conformance` against a driver that misbehaves for real: the test-only Vulkan layer
// VK_LAYER_RASTERCMP_hostile (tests/hostile_layer/) sits between rastercmp and lavapipe and, inside
// vkQueueSubmit of the scene 37 pixels wide, segfaults, aborts, calls exit(2), loses the device,
// writes into the result pipe, forks a helper, floods stderr, hangs, stops itself or closes its
// descriptors and hangs. Each costs that case alone (docs/reliability.md): the cases beside it
// pass, the run completes and fails, and a fault that comes back on the re-run is no Flake.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

constexpr int kFaultWidth = 37;  // the layer arms its fault on an image this wide

std::string scene(const std::string& name, int width) {
  return R"({"name": ")" + name + R"(", "width": )" + std::to_string(width) + R"(, "height": 10,
            "draws": [{"positions": [[-0.8, -0.7, 0.2], [0.9, -0.3, 0.6], [-0.1, 0.85, 0.9]]}]})";
}

EnvEdits hostile(const std::string& fault, const fs::path& dir) {
  return {{"VK_LAYER_PATH", RASTERCMP_HOSTILE_LAYER_DIR},
          {"VK_INSTANCE_LAYERS", "VK_LAYER_RASTERCMP_hostile"},
          {"RASTERCMP_HOSTILE_LAYER", fault + ":" + std::to_string(kFaultWidth)},
          {"RASTERCMP_HOSTILE_DIR", dir.string()}};
}

// Suite t.a, t.fault (the layer's scene), t.z, run with the default --timeout and one re-run: no
// case meant to pass can meet a deadline on a loaded machine.
struct Outcome {
  RunResult run;
  std::string what;
  nlohmann::json summary;
  std::map<std::string, nlohmann::json> cases;
};

Outcome run_beside_two_good_cases(const TempDir& tmp, const std::string& fault) {
  const fs::path suite = tmp / ("suite-" + fault), out = tmp / ("out-" + fault);
  fs::create_directories(suite);
  write_file(suite / "t.a.json", scene("t.a", 12));
  write_file(suite / "t.fault.json", scene("t.fault", kFaultWidth));
  write_file(suite / "t.z.json", scene("t.z", 12));
  const std::vector<std::string> args = {"conformance", "--suite", suite.string(), "--out", out.string()};
  Outcome o;
  o.run = run_cli(args, hostile(fault, tmp.path()));
  o.what = describe(args, o.run);
  if (fs::exists(out / "summary.json")) {
    o.summary = nlohmann::json::parse(read_file(out / "summary.json"));
    o.cases = cases_by_name(o.summary);
  }
  return o;
}

TEST(CliHostileDriver, ACrashExitOrStrayOutputInTheDriverCostsItsCaseOnly) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const std::map<std::string, std::string> expected_message = {
      {"segv", "signal 11"},
      {"abort", "signal 6"},
      {"exit2", "exited with code 2"},
      {"stray_line", "unexpected line on the result pipe: hostile driver was here"},
  };
  for (const auto& [fault, message] : expected_message) {
    SCOPED_TRACE(fault);
    const Outcome o = run_beside_two_good_cases(tmp, fault);
    ASSERT_EQ(o.run.exit_code, 1) << o.what;
    ASSERT_EQ(o.run.signal, 0) << o.what;
    EXPECT_EQ(o.summary.at("complete"), true) << o.what;
    EXPECT_EQ(o.summary.at("passed"), false) << o.what;
    EXPECT_EQ(o.cases.at("t.a").at("status"), "Pass") << o.what;
    EXPECT_EQ(o.cases.at("t.z").at("status"), "Pass") << o.what;
    // The fault comes back on the re-run: it never passed, so it is no Flake.
    const nlohmann::json& bad = o.cases.at("t.fault");
    EXPECT_EQ(bad.at("status"), "Crash") << bad.dump(1);
    EXPECT_NE(bad.at("message").get<std::string>().find(message), std::string::npos) << bad.dump(1);
  }
}

TEST(CliHostileDriver, ALostDeviceFailsItsCaseAndTheNextCaseGetsANewOne) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const Outcome o = run_beside_two_good_cases(tmp, "device_lost");
  ASSERT_EQ(o.run.exit_code, 1) << o.what;
  EXPECT_EQ(o.summary.at("complete"), true) << o.what;
  const nlohmann::json& bad = o.cases.at("t.fault");
  EXPECT_EQ(bad.at("status"), "Fail") << bad.dump(1);
  EXPECT_EQ(bad.at("verdict"), "InternalError") << bad.dump(1);
  EXPECT_NE(bad.at("message").get<std::string>().find("VK_ERROR_DEVICE_LOST"), std::string::npos) << bad.dump(1);
  EXPECT_EQ(o.cases.at("t.a").at("status"), "Pass") << o.what;
  EXPECT_EQ(o.cases.at("t.z").at("status"), "Pass") << o.what;
}

// A helper that inherits every descriptor and sleeps for ever, and 32 MiB on stderr: the cases pass,
// the run ends, and the helper ends with its case's process group.
TEST(CliHostileDriver, AHelperOrAFloodOfStderrLeavesEveryCasePassing) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  for (const std::string fault : {"helper", "stderr_flood"}) {
    SCOPED_TRACE(fault);
    const Outcome o = run_beside_two_good_cases(tmp, fault);
    ASSERT_EQ(o.run.exit_code, 0) << o.what;
    EXPECT_EQ(o.summary.at("passed"), true) << o.what;
    EXPECT_EQ(o.cases.at("t.fault").at("status"), "Pass") << o.what;
    EXPECT_LT(o.run.out.size() + o.run.err.size(), size_t(1) << 20) << "the flood reached the console";
  }
  const fs::path pid_file = tmp / "helper.pid";
  ASSERT_TRUE(fs::exists(pid_file)) << "the layer started no helper";
  const pid_t helper = pid_t(std::stol(read_file(pid_file)));
  EXPECT_TRUE(process_ends_soon(helper)) << "helper " << helper << " outlived the run";
}

// A driver that hangs, stops itself, or closes every descriptor and hangs: the deadline holds and
// the case is a Timeout. The case is alone in its suite with --timeout 2: no case meant to pass
// meets the short deadline.
TEST(CliHostileDriver, AHangingStoppedOrDeafDriverTimesOut) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  for (const std::string fault : {"hang", "stop", "close_fds_hang"}) {
    SCOPED_TRACE(fault);
    const fs::path suite = tmp / ("suite-" + fault), out = tmp / ("out-" + fault);
    fs::create_directories(suite);
    write_file(suite / "t.fault.json", scene("t.fault", kFaultWidth));
    const std::vector<std::string> args = {"conformance", "--suite", suite.string(), "--out",
                                           out.string(),  "--timeout", "2",   "--flake-retries", "0"};
    const RunResult r = run_cli(args, hostile(fault, tmp.path()));
    ASSERT_EQ(r.exit_code, 1) << describe(args, r);
    const nlohmann::json bad = cases_by_name(nlohmann::json::parse(read_file(out / "summary.json"))).at("t.fault");
    EXPECT_EQ(bad.at("status"), "Timeout") << bad.dump(1);
  }
}

}  // namespace
}  // namespace rastercmp::cli_test
