// Cases in child processes (compare/case_children.hpp): a crashing case and a hanging one cost
// that case only, are recorded as Crash and Timeout with what happened, and fail the run; a case
// that fails once and passes on its re-run is a Flake; --out is locked; temporary files an
// earlier run left are removed. The faults come from the test-only hook RASTERCMP_TEST_CASE_FAULT
// (compare/case_worker.hpp) on a suite of four tiny scenes.
#include <gtest/gtest.h>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <map>
#include <thread>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <regex>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

std::string scene(const std::string& name) {
  return R"({"name": ")" + name +
         R"(", "width": 12, "height": 10,
            "draws": [{"positions": [[-0.8, -0.7, 0.2], [0.9, -0.3, 0.6], [-0.1, 0.85, 0.9]]}]})";
}

// Four cases: a, crash, hang, once (in that order).
void write_suite(const fs::path& dir) {
  fs::create_directories(dir);
  for (const char* name : {"t.a", "t.crash", "t.hang", "t.once"})
    write_file(dir / (std::string(name) + ".json"), scene(name));
}

// Files an interrupted write would leave: ".STEM.tmpPID.EXT".
std::vector<std::string> temporaries_below(const fs::path& dir) {
  static const std::regex temporary(R"(\..*\.tmp[0-9]+(\.[A-Za-z0-9]+)?)");
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (std::regex_match(e.path().filename().string(), temporary)) found.push_back(e.path().string());
  return found;
}

// A Flake failed, then passed: a case that crashes and then fails on its re-run never passed, so
// it keeps failing the run (its first record, with the re-run's reason), and the run fails.
TEST(CliChildren, ACaseThatFailsAnotherWayOnItsReRunIsNoFlake) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  fs::create_directories(tmp / "suite");
  for (const char* name : {"t.a", "t.twice"}) write_file(tmp / "suite" / (std::string(name) + ".json"), scene(name));
  fs::create_directories(tmp / "faults");
  const EnvEdits faults = {{"RASTERCMP_TEST_CASE_FAULT", "crash_then_fail:t.twice"},
                           {"RASTERCMP_TEST_FAULT_DIR", (tmp / "faults").string()}};
  const fs::path out = tmp / "out";
  const std::vector<std::string> args = {"conformance", "--suite", (tmp / "suite").string(), "--out", out.string()};
  const RunResult r = run_cli(args, faults);
  const std::string what = describe(args, r);
  ASSERT_EQ(r.exit_code, 1) << what;
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary.at("passed"), false);
  auto cases = cases_by_name(summary);
  EXPECT_EQ(cases["t.a"]["status"], "Pass");
  EXPECT_EQ(cases["t.twice"]["status"], "Crash");
  EXPECT_NE(cases["t.twice"]["message"].get<std::string>().find("re-run 1: Fail"), std::string::npos)
      << cases["t.twice"].dump(1);
  EXPECT_EQ(read_file(out / "failures.csv"), "t.twice,Crash\n");
}

// A driver that exits with status 2 (the code of bad input) or writes a line into the result pipe
// during a case costs that case (Crash, with the reason), never the run: the other cases run, the
// run completes with exit 1.
TEST(CliChildren, ADriversExitCodeOrStrayOutputCostsItsCaseOnly) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  fs::create_directories(tmp / "suite");
  for (const char* name : {"t.a", "t.exit", "t.stray", "t.z"})
    write_file(tmp / "suite" / (std::string(name) + ".json"), scene(name));
  const EnvEdits faults = {{"RASTERCMP_TEST_CASE_FAULT", "exit2:t.exit;stray_line:t.stray"}};
  const fs::path out = tmp / "out";
  const std::vector<std::string> args = {"conformance",     "--suite", (tmp / "suite").string(), "--out", out.string(),
                                         "--flake-retries", "0"};
  const RunResult r = run_cli(args, faults);
  const std::string what = describe(args, r);
  ASSERT_EQ(r.exit_code, 1) << what;
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary.at("complete"), true) << what;
  auto cases = cases_by_name(summary);
  EXPECT_EQ(cases["t.a"]["status"], "Pass");
  EXPECT_EQ(cases["t.z"]["status"], "Pass");
  EXPECT_EQ(cases["t.exit"]["status"], "Crash");
  EXPECT_NE(cases["t.exit"]["message"].get<std::string>().find("exited with code 2"), std::string::npos)
      << cases["t.exit"].dump(1);
  EXPECT_EQ(cases["t.stray"]["status"], "Crash");
  EXPECT_NE(cases["t.stray"]["message"].get<std::string>().find("unexpected line on the result pipe: a driver's line"),
            std::string::npos)
      << cases["t.stray"].dump(1);
}

// A suite of case `name` alone and the conformance command line that runs it into tmp/out with
// --timeout 2 and no re-run: a case meant to time out, with no case meant to pass beside it that
// a loaded machine could push past the deadline.
std::vector<std::string> alone_with_a_short_timeout(const TempDir& tmp, const std::string& name) {
  fs::create_directories(tmp / "suite");
  write_file(tmp / "suite" / (name + ".json"), scene(name));
  return {"conformance", "--suite", (tmp / "suite").string(), "--out", (tmp / "out").string(),
          "--timeout",   "2",       "--flake-retries",        "0"};
}

// A driver that forks a helper which inherits the pipes and never exits: each child is its own
// process group, so the end of the child ends the helper too, and the run does not wait for the
// helper's end of file. Without that the run never ended.
TEST(CliChildren, AHelperTheDriverForksNeitherHoldsTheRunNorOutlivesIt) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  fs::create_directories(tmp / "suite");
  for (const char* name : {"t.a", "t.helper"}) write_file(tmp / "suite" / (std::string(name) + ".json"), scene(name));
  fs::create_directories(tmp / "faults");
  const EnvEdits faults = {{"RASTERCMP_TEST_CASE_FAULT", "helper:t.helper"},
                           {"RASTERCMP_TEST_FAULT_DIR", (tmp / "faults").string()}};
  const std::vector<std::string> args = {"conformance", "--suite", (tmp / "suite").string(), "--out",
                                         (tmp / "out").string()};
  const RunResult r = run_cli(args, faults);
  ASSERT_EQ(r.exit_code, 0) << describe(args, r);
  const pid_t helper = pid_t(std::stol(read_file(tmp / "faults" / "t.helper.helper")));
  EXPECT_TRUE(process_ends_soon(helper)) << "helper " << helper << " outlived the run";
}

// A driver that closes every descriptor and hangs: both pipes reach end of file while the process
// lives. The deadline still holds (Timeout), and the run ends. Without it the parent blocked in
// waitpid for good, deaf to SIGINT. Only this case is in the suite: no case meant to pass meets
// the short timeout.
TEST(CliChildren, AChildThatClosesItsPipesAndHangsTimesOut) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const std::vector<std::string> args = alone_with_a_short_timeout(tmp, "t.closer");
  const RunResult r = run_cli(args, {{"RASTERCMP_TEST_CASE_FAULT", "close_fds_hang:t.closer"}});
  ASSERT_EQ(r.exit_code, 1) << describe(args, r);
  auto cases = cases_by_name(nlohmann::json::parse(read_file(tmp / "out" / "summary.json")));
  EXPECT_EQ(cases["t.closer"]["status"], "Timeout") << cases["t.closer"].dump(1);
}

// A crash costs its case, a case that fails once and passes on its re-run is a Flake. The default
// --timeout: no case meant to pass can meet a deadline on a loaded machine (docs/reliability.md);
// the hang has a test of its own below, alone in its suite.
TEST(CliChildren, ARunSurvivesACrashAndTellsAFlakeFromAFailure) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  write_suite(tmp / "suite");
  fs::remove(tmp / "suite" / "t.hang.json");
  fs::create_directories(tmp / "faults");
  const EnvEdits faults = {{"RASTERCMP_TEST_CASE_FAULT", "crash:t.crash;fail_once:t.once"},
                           {"RASTERCMP_TEST_FAULT_DIR", (tmp / "faults").string()}};
  const fs::path out = tmp / "out";
  write_file(tmp / "stale", "");
  fs::create_directories(out / "report");
  write_file(out / ".summary.tmp2147483000.json", "{\"passed\": tr");  // a run killed mid-write left these
  write_file(out / "report" / ".cpu.tmp2147483001.png", "half a PNG");
  const std::vector<std::string> args = {"conformance", "--suite", (tmp / "suite").string(), "--out", out.string()};
  const RunResult r = run_cli(args, faults);
  const std::string what = describe(args, r);
  ASSERT_EQ(r.signal, 0) << what;
  ASSERT_EQ(r.exit_code, 1) << what;

  EXPECT_EQ(read_file(out / "results.csv").find("t.a,Pass,"), 0u) << read_file(out / "results.csv");
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary.at("complete"), true);
  EXPECT_EQ(summary.at("passed"), false);
  auto cases = cases_by_name(summary);
  ASSERT_EQ(cases.size(), 3u) << summary.dump(1);
  EXPECT_EQ(cases["t.a"]["status"], "Pass");
  EXPECT_EQ(cases["t.crash"]["status"], "Crash");
  EXPECT_EQ(cases["t.crash"]["verdict"], "Crash");
  const std::string crash = cases["t.crash"]["message"];
  EXPECT_NE(crash.find("signal 11 (SIGSEGV"), std::string::npos) << crash;
  EXPECT_NE(crash.find("| test-only fault: crash in t.crash"), std::string::npos) << "the child's last stderr lines\n"
                                                                                  << crash;
  EXPECT_EQ(cases["t.once"]["status"], "Flake");
  EXPECT_NE(cases["t.once"]["message"].get<std::string>().find("re-run 1: Pass"), std::string::npos);
  EXPECT_EQ(read_file(out / "failures.csv"), "t.crash,Crash\n");
  const std::string junit = read_file(out / "junit.xml");
  EXPECT_NE(junit.find("tests=\"3\" failures=\"0\" errors=\"1\""), std::string::npos) << junit;
  EXPECT_TRUE(temporaries_below(out).empty()) << temporaries_below(out).front();
  EXPECT_FALSE(fs::exists(out / ".retry"));
  EXPECT_NE(r.err.find("removed 2 temporary file(s)"), std::string::npos) << what;

  // A baseline that expects the crash passes; two jobs at a time give the same records.
  write_file(tmp / "fails.txt", "t.crash,Crash\n");
  const fs::path two = tmp / "two_jobs";
  const std::vector<std::string> again = {
      "conformance", "--suite", (tmp / "suite").string(), "--baseline", (tmp / "fails.txt").string(),
      "--jobs",      "2",       "--flake-retries",        "0",          "--out",
      two.string()};
  const RunResult r2 = run_cli(again, faults);
  EXPECT_EQ(r2.exit_code, 0) << describe(again, r2);
  auto cases2 = cases_by_name(nlohmann::json::parse(read_file(two / "summary.json")));
  EXPECT_EQ(cases2["t.crash"]["status"], "ExpectedFail");
  EXPECT_EQ(cases2["t.once"]["status"], "Pass");  // its one failure was spent above
  EXPECT_EQ(read_file(two / "failures.csv"), "");
}

// A hang is killed at --timeout and is a Timeout with the time and the child's last output. Alone
// in its suite, so the short timeout meets no case meant to pass; a baseline that expects it passes.
TEST(CliChildren, AHangIsATimeoutWithTheChildsLastOutput) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const EnvEdits faults = {{"RASTERCMP_TEST_CASE_FAULT", "hang:t.hang"}};
  const std::vector<std::string> args = alone_with_a_short_timeout(tmp, "t.hang");
  const RunResult r = run_cli(args, faults);
  ASSERT_EQ(r.exit_code, 1) << describe(args, r);
  auto cases = cases_by_name(nlohmann::json::parse(read_file(tmp / "out" / "summary.json")));
  EXPECT_EQ(cases["t.hang"]["status"], "Timeout");
  const std::string hang = cases["t.hang"]["message"];
  EXPECT_NE(hang.find("ran past --timeout 2 s"), std::string::npos) << hang;
  EXPECT_NE(hang.find("| test-only fault: hang in t.hang"), std::string::npos) << hang;
  EXPECT_EQ(read_file(tmp / "out" / "failures.csv"), "t.hang,Timeout\n");
  write_file(tmp / "fails.txt", "t.hang,Timeout\n");
  std::vector<std::string> expected = args;
  expected.insert(expected.end(), {"--baseline", (tmp / "fails.txt").string()});
  expected[4] = (tmp / "expected").string();
  const RunResult r2 = run_cli(expected, faults);
  EXPECT_EQ(r2.exit_code, 0) << describe(expected, r2);
}

TEST(CliChildren, ASecondRunIntoALockedFolderExits2NamingTheHolder) {
  const TempDir tmp;
  write_suite(tmp / "suite");
  const fs::path out = tmp / "out";
  HeldOutputLock lock(out);  // as a running conformance would
  const TreeSnapshot before = files_of(snapshot_tree(out));
  const std::vector<std::string> args = {"conformance", "--suite", (tmp / "suite").string(), "--out", out.string()};
  const RunResult r = run_cli(args, kNoVulkanDriver);  // exit 2 before any Vulkan: the lock comes first
  // merge into the same folder waits for no one either: exit 2 naming the holder.
  const std::vector<std::string> merge = {"merge", out.string(), (tmp / "suite").string()};
  const RunResult m = run_cli(merge);
  lock.release();
  EXPECT_EQ(r.exit_code, 2) << describe(args, r);
  EXPECT_NE(r.err.find("pid 31337"), std::string::npos) << describe(args, r);
  EXPECT_EQ(m.exit_code, 2) << describe(merge, m);
  EXPECT_NE(m.err.find("pid 31337"), std::string::npos) << describe(merge, m);
  EXPECT_EQ(files_of(snapshot_tree(out)), before);
}

// A full disk, made with a file-size limit (ulimit -f; rastercmp ignores SIGXFSZ, so a write past it
// fails with EFBIG as one past a full disk fails with ENOSPC, and the signal does not kill it): the
// command fails with exit 2 and leaves no file under a final name that is not whole, and no
// temporary file.
TEST(CliChildren, AFullDiskLeavesNoHalfFileUnderAFinalName) {
  const TempDir tmp;
  write_file(tmp / "big.json", R"({"name": "t.big", "width": 256, "height": 256, "depth_format": "d32_sfloat",
    "draws": [{"positions": [[-0.9, -0.9, 0.2], [0.9, -0.8, 0.6], [-0.1, 0.9, 0.9]]}]})");
  for (const int kib : {1, 8, 40}) {
    const fs::path out = tmp / ("out" + std::to_string(kib));
    const std::string command = "ulimit -f " + std::to_string(kib) + "; exec " + kBinary.string() + " render " +
                                (tmp / "big.json").string() + " --backend cpu --out " + out.string() + " >" +
                                (tmp / "log").string() + " 2>&1";
    const int status = std::system(("sh -c \"" + command + "\"").c_str());
    ASSERT_TRUE(WIFEXITED(status)) << command;
    EXPECT_EQ(WEXITSTATUS(status), 2) << command << "\n" << read_file(tmp / "log");
    EXPECT_NE(read_file(tmp / "log").find("could not write"), std::string::npos) << read_file(tmp / "log");
    // A folder the failed command made and left empty is removed again (docs/reliability.md).
    if (!fs::is_directory(out)) continue;
    EXPECT_TRUE(temporaries_below(out).empty()) << temporaries_below(out).front();
    // What is there is whole: what a run without the limit writes, byte for byte.
    const fs::path whole = tmp / ("whole" + std::to_string(kib));
    ASSERT_EQ(run_cli({"render", (tmp / "big.json").string(), "--backend", "cpu", "--out", whole.string()}).exit_code,
              0);
    for (const auto& e : fs::directory_iterator(out))
      EXPECT_EQ(read_file(e.path()), read_file(whole / e.path().filename())) << e.path() << " is not whole";
  }
}

// A conformance run onto a full disk (ulimit -f, as above), the limit met at the first write or
// in the middle of the run: exit 2 naming the file, no verdict that reads as a pass (summary.json
// absent, or complete and passed false), summary.json and results.csv agreeing on the cases, and no
// temporary file left.
TEST(CliChildren, AFullDiskEndsAConformanceRunWithExit2AndNoPass) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  fs::create_directories(tmp / "suite");
  for (int k = 0; k < 12; ++k) {
    const std::string name = "t.c" + std::to_string(10 + k);
    write_file(tmp / "suite" / (name + ".json"), scene(name));
  }
  for (const int kib : {1, 12, 16, 24}) {  // at 16 and 24 KiB summary.json, the largest file, meets the limit mid-run
    const fs::path out = tmp / ("out" + std::to_string(kib));
    const std::string command = "ulimit -f " + std::to_string(kib) + "; exec " + kBinary.string() +
                                " conformance --suite " + (tmp / "suite").string() + " --out " + out.string() + " >" +
                                (tmp / "log").string() + " 2>&1";
    const int status = std::system(("sh -c \"" + command + "\"").c_str());
    const std::string log = read_file(tmp / "log");
    ASSERT_TRUE(WIFEXITED(status)) << command;
    EXPECT_EQ(WEXITSTATUS(status), 2) << command << "\n" << log;
    EXPECT_NE(log.find("could not write"), std::string::npos) << log;
    EXPECT_TRUE(temporaries_below(out).empty()) << temporaries_below(out).front();
    if (!fs::exists(out / "summary.json")) continue;
    const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
    EXPECT_EQ(summary.at("complete"), false) << "limit " << kib << " KiB";
    EXPECT_EQ(summary.at("passed"), false) << "limit " << kib << " KiB";
    // results.csv (CASE,STATUS,SECONDS) says of every case what summary.json says: the files are
    // written together (a summary.json one case behind results.csv before).
    std::map<std::string, std::string> csv_status;
    for (const std::string& line : lines_of(read_file(out / "results.csv"))) {
      const auto comma = line.find(',');
      if (comma == std::string::npos) continue;
      csv_status[line.substr(0, comma)] = line.substr(comma + 1, line.find(',', comma + 1) - comma - 1);
    }
    for (const nlohmann::json& c : summary.at("cases"))
      EXPECT_EQ(csv_status[c.at("scene").get<std::string>()], c.at("status").get<std::string>()) << c.at("scene");
    const size_t missing_in_csv = size_t(
        std::count_if(csv_status.begin(), csv_status.end(), [](const auto& e) { return e.second == "Missing"; }));
    EXPECT_EQ(missing_in_csv, summary.at("statuses").value("Missing", size_t(0))) << summary.at("statuses").dump();
    EXPECT_EQ(csv_status.size(), size_t(12));
  }
}

}  // namespace
}  // namespace rastercmp::cli_test
