// SIGINT during `rastercmp conformance` (docs/compare.md "Conformance runs"): the current case
// finishes, every output is written and parses, not_run.txt lists the rest, the run says how to
// resume and exits 130; resuming from not_run.txt and merging gives the whole run's results.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

constexpr int kExitInterrupted = 130;
const char* const kCases = "rastercmp.depth.compare.*";  // 11 small cases

// The case rows of results.csv (`name,status,duration`, the header line skipped).
std::vector<std::string> result_rows(const fs::path& results_csv) {
  std::vector<std::string> rows;
  for (const std::string& line : lines_of(read_file(results_csv)))
    if (!line.empty() && line.rfind("name,", 0) != 0) rows.push_back(line);
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
  EXPECT_NE(said.find("rastercmp merge"), std::string::npos) << what;

  // Resume as told, merge, and compare with one uninterrupted run.
  const fs::path resumed = tmp / "resumed", merged = tmp / "merged", whole = tmp / "whole";
  const std::vector<std::string> resume = {
      "conformance", "--case", kCases, "--caselist", (out / "not_run.txt").string(), "--out", resumed.string()};
  const RunResult rr = run_cli(resume);
  ASSERT_TRUE(rr.exit_code == 0 || rr.exit_code == 1) << describe(resume, rr);
  const std::vector<std::string> merge = {"merge", merged.string(), out.string(), resumed.string()};
  const RunResult rm = run_cli(merge);
  ASSERT_TRUE(rm.exit_code == 0 || rm.exit_code == 1) << describe(merge, rm);
  const std::vector<std::string> full = {"conformance", "--case", kCases, "--out", whole.string()};
  const RunResult rf = run_cli(full);
  ASSERT_TRUE(rf.exit_code == 0 || rf.exit_code == 1) << describe(full, rf);
  EXPECT_EQ(rm.exit_code, rf.exit_code);
  for (const char* name : {"summary.json", "failures.csv", "report/index.html"})
    EXPECT_TRUE(read_file(merged / name) == read_file(whole / name)) << name << " of the merge differs";
}

}  // namespace
}  // namespace rastercmp::cli_test
