// SIGINT during `rastercmp conformance` (docs/compare.md "Conformance runs"): the current case
// finishes, every output is written and parses, not_run.txt lists the rest, the run says how to
// resume and exits 130; pasting the printed commands (resume, then merge) gives the whole run's
// results. SIGTERM and SIGHUP do the same (exit 143, 129); after kill -9 every output still
// reads as not passed.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

constexpr int kExitInterrupted = 130;
const char* const kCases = "rastercmp.depth.compare.*";  // 11 small cases

// The rows of results.csv (`name,status,duration`) of finished cases: not the Missing rows of
// the cases without a result yet.
std::vector<std::string> result_rows(const fs::path& results_csv) {
  std::vector<std::string> rows;
  for (const std::string& line : lines_of(read_file(results_csv)))
    if (!line.empty() && line.find(",Missing,") == std::string::npos) rows.push_back(line);
  return rows;
}

// Waits until results.csv has a finished case (or `limit` passes).
bool wait_for_first_case(const fs::path& results_csv, std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < deadline) {
    if (fs::exists(results_csv) && !result_rows(results_csv).empty()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

std::set<std::string> names_of(const nlohmann::json& summary) {
  std::set<std::string> names;
  for (const nlohmann::json& c : summary.at("cases")) names.insert(c.at("scene").get<std::string>());
  return names;
}

TEST(CliInterrupt, SigintFinishesTheCaseWritesEverythingAndSaysHowToResume) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const fs::path out = tmp / "out";
  const std::vector<std::string> args = {"conformance", "--case", kCases, "--out", out.string()};
  Child child(args);
  ASSERT_TRUE(wait_for_first_case(out / "results.csv", std::chrono::seconds(120))) << "no case finished";
  child.send_signal(SIGINT);
  const RunResult r = child.wait();
  const std::string what = describe(args, r);
  ASSERT_EQ(r.signal, 0) << what;
  ASSERT_EQ(r.exit_code, kExitInterrupted) << what;

  // results.csv: complete rows only, each `name,status,duration` with a number for the duration.
  const std::vector<std::string> rows = result_rows(out / "results.csv");
  ASSERT_GE(rows.size(), 1u);
  std::set<std::string> finished;
  for (const std::string& row : rows) {
    const size_t c1 = row.find(','), c2 = row.rfind(',');
    ASSERT_TRUE(c1 != std::string::npos && c2 > c1) << row;
    EXPECT_NO_THROW((void)std::stod(row.substr(c2 + 1))) << row;
    finished.insert(row.substr(0, c1));
  }
  std::vector<std::string> not_run;  // a case list: `#` comment lines, then one name per line
  for (const std::string& line : lines_of(read_file(out / "not_run.txt")))
    if (!line.empty() && line[0] != '#') not_run.push_back(line);
  ASSERT_FALSE(not_run.empty()) << "the run ended before the interrupt was seen; nothing to resume\n" << what;
  EXPECT_EQ(finished.size() + not_run.size(), 11u);
  for (const std::string& name : not_run) EXPECT_EQ(finished.count(name), 0u) << name << " both run and not run";

  nlohmann::json summary;
  ASSERT_NO_THROW(summary = nlohmann::json::parse(read_file(out / "summary.json")));
  EXPECT_EQ(names_of(summary), finished);
  EXPECT_EQ(summary.at("not_run").size(), not_run.size());
  for (const char* name : {"failures.csv", "junit.xml", "report/index.html"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;

  const std::string said = r.out + r.err;
  EXPECT_NE(said.find("--caselist " + (out / "not_run.txt").string()), std::string::npos) << what;
  EXPECT_EQ(summary.at("complete"), false);
  EXPECT_EQ(summary.at("passed"), false);

  // Paste the two printed commands as they are (a shell runs them), then compare with one
  // uninterrupted run.
  const std::vector<std::string> out_lines = lines_of(r.out);
  std::vector<std::string> pasted;
  for (size_t i = 0; i + 1 < out_lines.size(); ++i)
    if (out_lines[i] == "resume with:" || out_lines[i] == "then merge:") pasted.push_back(out_lines[i + 1]);
  ASSERT_EQ(pasted.size(), 2u) << what;
  for (const std::string& command : pasted) {
    const int status = std::system((command + " >/dev/null 2>&1").c_str());
    ASSERT_TRUE(WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 1)) << command;
  }
  const fs::path merged = out.string() + "-merged", whole = tmp / "whole";
  const std::vector<std::string> full = {"conformance", "--case", kCases, "--out", whole.string()};
  const RunResult rf = run_cli(full);
  ASSERT_TRUE(rf.exit_code == 0 || rf.exit_code == 1) << describe(full, rf);
  for (const char* name : {"summary.json", "failures.csv", "report/index.html"})
    EXPECT_TRUE(read_file(merged / name) == read_file(whole / name)) << name << " of the merge differs";
}

// A CI cancel (SIGTERM) or a closed terminal (SIGHUP) stops the run as SIGINT does.
TEST(CliInterrupt, SigtermAndSighupStopTheRunHonestly) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  for (const int signal : {SIGTERM, SIGHUP}) {
    const TempDir tmp;
    const fs::path out = tmp / "out";
    const std::vector<std::string> args = {"conformance", "--case", kCases, "--out", out.string()};
    Child child(args);
    ASSERT_TRUE(wait_for_first_case(out / "results.csv", std::chrono::seconds(120))) << "no case finished";
    child.send_signal(signal);
    const RunResult r = child.wait();
    const std::string what = describe(args, r);
    ASSERT_EQ(r.signal, 0) << what;
    EXPECT_EQ(r.exit_code, 128 + signal) << what;
    const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
    EXPECT_EQ(summary.at("interrupted"), true) << what;
    EXPECT_EQ(summary.at("complete"), false);
    EXPECT_EQ(summary.at("passed"), false);
    EXPECT_FALSE(summary.at("not_run").empty()) << what;
    EXPECT_TRUE(fs::exists(out / "not_run.txt"));
    EXPECT_NE(read_file(out / "failures.csv").find(",Missing\n"), std::string::npos);
  }
}

// `nohup rastercmp conformance`: a SIGHUP the caller ignores stays ignored, so the hang-up does not
// stop the run; it finishes complete (SIGHUP is ignored here before the child is spawned, as nohup
// does before exec, and posix_spawn keeps it ignored).
TEST(CliInterrupt, AnIgnoredSighupStaysIgnoredAsUnderNohup) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const fs::path out = tmp / "out";
  const std::vector<std::string> args = {"conformance", "--case", kCases, "--out", out.string()};
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGHUP, &ignore, &previous);
  Child child(args);
  sigaction(SIGHUP, &previous, nullptr);
  ASSERT_TRUE(wait_for_first_case(out / "results.csv", std::chrono::seconds(120))) << "no case finished";
  child.send_signal(SIGHUP);
  const RunResult r = child.wait();
  const std::string what = describe(args, r);
  ASSERT_EQ(r.signal, 0) << what;
  EXPECT_EQ(r.exit_code, 0) << what;
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary.at("complete"), true) << what;
  EXPECT_EQ(summary.at("interrupted"), false);
}

// kill -9 leaves no chance to write anything: what is there must already read as not passed.
TEST(CliInterrupt, AKilledRunNeverReadsAsAPass) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const fs::path out = tmp / "out";
  const std::vector<std::string> args = {"conformance", "--case", kCases, "--out", out.string()};
  Child child(args);
  ASSERT_TRUE(wait_for_first_case(out / "results.csv", std::chrono::seconds(120))) << "no case finished";
  child.send_signal(SIGKILL);
  child.wait();
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary.at("complete"), false);
  EXPECT_EQ(summary.at("passed"), false);
  EXPECT_EQ(summary.at("not_run").size() + summary.at("cases").size(), 11u);
  const std::string junit = read_file(out / "junit.xml");
  EXPECT_NE(junit.find("tests=\"11\""), std::string::npos) << junit;
  EXPECT_NE(junit.find("type=\"Missing\""), std::string::npos);
  EXPECT_EQ(lines_of(read_file(out / "results.csv")).size(), 11u);  // every case: a result or Missing
}

}  // namespace
}  // namespace rastercmp::cli_test
