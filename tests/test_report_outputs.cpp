// The machine-readable outputs (results.csv, failures.csv, junit.xml, summary.json, compare
// JSON) parse back, and `merge` of shard folders equals the outputs of the whole run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/detail/pugixml/pugixml.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "compare/case_record.hpp"
#include "compare/expectations.hpp"
#include "compare/merge.hpp"
#include "compare/report.hpp"
#include "compare/run_outputs.hpp"
#include "compare/run_publish.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace {
namespace fs = std::filesystem;

DiffSummary some_diff(uint64_t missing, uint64_t depth_mismatches) {
  DiffSummary d;
  d.width = 16;
  d.height = 8;
  d.samples = 1;
  d.depth_format = DepthFormat::X8D24Unorm;
  d.depth_compared = true;
  d.pixels = 128;
  d.samples_compared = 128;
  d.missing = missing;
  d.covered_match = 40;
  d.bad_pixels = missing + depth_mismatches;
  d.depth.mismatches = depth_mismatches;
  if (depth_mismatches) {
    d.depth.max_raw = 2048;
    d.depth.max_r = 1024;
    d.depth.p50_raw = 3;
    d.depth.p95_raw = 100;
    d.depth.p50_r = 1.5;
    d.depth.p95_r = 50;
    d.depth.max_at = {5, 6, 0};
    d.depth.max_expected_raw = 0x800000;
    d.depth.max_actual_raw = 0x800800;
  }
  if (missing) {
    BadSample b;
    b.at = {1, 2, 0};
    b.kind = "missing";
    b.expected_owner = encode_owner(0, 3);
    b.has_depth = true;
    b.expected_depth_raw = 0x400000;
    b.actual_depth_raw = 0xFFFFFF;
    d.first_bad.push_back(b);
  }
  return d;
}

CaseRecord record(const std::string& name, Verdict verdict, std::string status, bool fails_run, double duration_s) {
  CaseRecord c;
  c.name = name;
  c.source = "/suite/" + name + ".json";
  c.width = 16;
  c.height = 8;
  c.verdict = verdict;
  c.message = "why: <" + name + "> & \"quoted\"";
  c.status = std::move(status);
  c.fails_run = fails_run;
  c.duration_s = duration_s;
  if (verdict != Verdict::NotSupported) c.diff = some_diff(verdict == Verdict::Pass ? 0 : 2, 1);
  if (verdict == Verdict::Pass) c.diff = some_diff(0, 0);
  return c;
}

std::vector<CaseRecord> sample_records() {
  std::vector<CaseRecord> r;
  r.push_back(record("rastercmp.a.pass", Verdict::Pass, "Pass", false, 0.25));
  r.push_back(record("rastercmp.b.fail", Verdict::Fail, "Fail", true, 1.5));
  r.push_back(record("rastercmp.c.expected", Verdict::Fail, "ExpectedFail", false, 0.5));
  r.back().expectation = "Fail";
  r.back().expectation_reason = "no tie rule, \"quoted\"";  // parses back with the rest
  r.back().cpu_method = "fill=scanline depth=bilinear";
  r.push_back(record("rastercmp.d.flaky", Verdict::Fail, "KnownFlake", false, 0.125));
  r.push_back(record("rastercmp.e.unsupported", Verdict::NotSupported, "Skip", false, 0.01));
  r.push_back(record("rastercmp.f.improved", Verdict::Pass, "UnexpectedImprovement(Pass)", true, 0.75));
  r.back().expectation = "Fail";
  r.push_back(record("rastercmp.g.lost", Verdict::InternalError, "Fail", true, 2.0));
  r.back().diff.reset();
  return r;
}

RunInfo sample_info() {
  return RunInfo{"lavapipe", "llvmpipe (LLVM 15.0.6, 256 bits)", "Mesa 22.3.6", true, true, false, {}, ""};
}

// A fresh folder for one test, removed when the test ends (one per process: ctest runs tests in
// parallel processes).
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(fs::temp_directory_path() / ("rastercmp_test_report_outputs_" + std::to_string(getpid()) + "_" + name)) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

TEST(ResultsCsv, LinesParseBackWithDurations) {
  std::string csv;
  for (const CaseRecord& c : sample_records()) csv += results_csv_line(c);
  EXPECT_EQ(results_csv_line(sample_records()[1]), "rastercmp.b.fail,Fail,1.500\n");
  const auto durations = parse_results_csv(csv, "results.csv");
  ASSERT_EQ(durations.size(), 7u);
  EXPECT_DOUBLE_EQ(durations.at("rastercmp.g.lost"), 2.0);
  EXPECT_DOUBLE_EQ(durations.at("rastercmp.f.improved"), 0.75);
  EXPECT_THROW(parse_results_csv("name-only\n", "results.csv"), InputError);
}

// A run not finished (or killed) lists the cases without a result as Missing, everywhere.
TEST(ResultsCsv, CasesWithoutAResultAreMissingRows) {
  RunInfo running = sample_info();
  running.complete = false;
  running.not_run = {"rastercmp.z.later"};
  const auto records = sample_records();
  const std::string csv = results_csv(running, records);
  EXPECT_TRUE(csv.ends_with("\nrastercmp.z.later,Missing,0.000\n")) << csv;
  EXPECT_EQ(parse_results_csv(csv, "results.csv").size(), records.size() + 1);
  EXPECT_NE(failures_csv(running, records).find("rastercmp.z.later,Missing\n"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(summary_json(running, records));
  EXPECT_EQ(j["complete"], false);
  EXPECT_EQ(j["passed"], false);
  EXPECT_EQ(j["statuses"]["Missing"], 1);
  // Even with every finished case passing, a run that is not complete does not pass.
  std::vector<CaseRecord> passing = {records[0]};
  RunInfo unfinished = sample_info();
  unfinished.complete = false;
  EXPECT_FALSE(run_passed(unfinished, passing));
  EXPECT_TRUE(run_passed(sample_info(), passing));
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(junit_xml(running, records).c_str()));
  const pugi::xml_node later =
      doc.child("testsuites").child("testsuite").find_child_by_attribute("testcase", "name", "later");
  EXPECT_STREQ(later.child("failure").attribute("type").value(), "Missing");
}

// failures.csv is deqp-runner's: the cases whose status fails the run (never ExpectedFail,
// Flake, KnownFlake or Skip), with that status; added to the baseline, the run passes.
TEST(FailuresCsv, ListsWhatFailsTheRunAndServesAsTheNextBaseline) {
  const auto records = sample_records();
  const std::string csv = failures_csv(sample_info(), records);
  EXPECT_EQ(csv, "rastercmp.b.fail,Fail\nrastercmp.f.improved,UnexpectedImprovement(Pass)\nrastercmp.g.lost,Fail\n");
  Expectations next;
  next.baseline = parse_baseline("rastercmp.c.expected,Fail\n", "fails.txt");
  for (const auto& [name, status] : parse_baseline(csv, "failures.csv")) next.baseline[name] = status;
  for (const CaseRecord& c : records) {
    if (c.status != "KnownFlake") {
      EXPECT_FALSE(judge_outcome(c.name, c.verdict, next).fails_run) << c.name;
    }
  }
}

TEST(JUnit, IsWellFormedAndCountsFailures) {
  const auto records = sample_records();
  RunInfo info = sample_info();
  info.not_run = {"rastercmp.h.missing"};
  const std::string xml = junit_xml(info, records);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_string(xml.c_str());
  ASSERT_TRUE(parsed) << parsed.description();
  const pugi::xml_node suite = doc.child("testsuites").child("testsuite");
  EXPECT_EQ(suite.attribute("tests").as_int(), 8);
  EXPECT_EQ(suite.attribute("failures").as_int(), 4);  // Fail, UnexpectedImprovement, Fail (InternalError), Missing
  EXPECT_EQ(suite.attribute("errors").as_int(), 0);    // Crash only
  EXPECT_EQ(suite.attribute("skipped").as_int(), 1);   // Skip
  int cases = 0;
  for (pugi::xml_node tc : suite.children("testcase")) {
    ++cases;
    EXPECT_FALSE(std::string(tc.attribute("classname").value()).empty());
    EXPECT_TRUE(tc.attribute("time"));
  }
  EXPECT_EQ(cases, 8);
  const pugi::xml_node fail = suite.find_child_by_attribute("testcase", "name", "fail");
  EXPECT_STREQ(fail.attribute("classname").value(), "rastercmp.b");
  EXPECT_STREQ(fail.child("failure").attribute("type").value(), "Fail");
  EXPECT_NE(std::string(fail.child("failure").attribute("message").value()).find("<rastercmp.b.fail> & \"quoted\""),
            std::string::npos);
  EXPECT_TRUE(suite.find_child_by_attribute("testcase", "name", "unsupported").child("skipped"));
  EXPECT_TRUE(suite.find_child_by_attribute("testcase", "name", "lost").child("failure"));
  EXPECT_TRUE(suite.find_child_by_attribute("testcase", "name", "missing").child("failure"));
}

TEST(SummaryJson, IsDeterministicAndParsesBack) {
  auto records = sample_records();
  const std::string text = summary_json(sample_info(), records);
  for (CaseRecord& c : records) c.duration_s *= 3;  // durations never reach summary.json
  EXPECT_EQ(summary_json(sample_info(), records), text);
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["cases_run"], 7);
  EXPECT_EQ(j["passed"], false);
  EXPECT_EQ(j["verdicts"]["Fail"], 3);
  EXPECT_EQ(j["statuses"]["UnexpectedImprovement(Pass)"], 1);
  EXPECT_EQ(text.find("duration"), std::string::npos);
  EXPECT_EQ(text.find("time"), std::string::npos);
  const ParsedSummary back = parse_summary_json(text, "summary.json");
  EXPECT_EQ(back.info, sample_info());
  ASSERT_EQ(back.records.size(), records.size());
  for (size_t i = 0; i < records.size(); ++i) {
    CaseRecord expected = records[i];
    expected.duration_s = 0;
    EXPECT_EQ(back.records[i], expected) << records[i].name;
  }
  EXPECT_THROW(parse_summary_json("{\"profile\": 3}", "summary.json"), InputError);
}

TEST(CompareJson, HasThePerSceneFieldsAndNullsWhenNotCompared) {
  const auto records = sample_records();
  const nlohmann::json fail = nlohmann::json::parse(case_to_json(records[1], false).dump());
  for (const char* key :
       {"scene", "width", "height", "pixels", "coverage_mismatches", "depth_mismatches", "max_depth_error", "verdict",
        "missing", "unexpected", "wrong_owner", "allowed", "depth_p50", "depth_p95", "max_depth_at", "first_bad"})
    EXPECT_TRUE(fail.contains(key)) << key;
  EXPECT_EQ(fail["verdict"], "Fail");
  EXPECT_EQ(fail["coverage_mismatches"], 2);
  EXPECT_EQ(fail["max_depth_error"], 2048);
  EXPECT_EQ(fail["depth_unit"], "LSB");
  EXPECT_EQ(fail["max_depth_at"]["x"], 5);
  EXPECT_EQ(fail["first_bad"][0]["kind"], "missing");
  EXPECT_FALSE(fail.contains("status"));
  const nlohmann::json unsupported = nlohmann::json::parse(case_to_json(records[4], false).dump());
  EXPECT_EQ(unsupported["verdict"], "NotSupported");
  EXPECT_TRUE(unsupported["coverage_mismatches"].is_null());
  EXPECT_EQ(unsupported["pixels"], 128);
}

// Writes a conformance output folder as a run over `records` would leave it.
void write_shard(const fs::path& dir, const RunInfo& info, const std::vector<CaseRecord>& records) {
  fs::create_directories(dir / "report");
  std::string csv;
  for (const CaseRecord& c : records) {
    csv += results_csv_line(c);
    fs::create_directories(dir / "report" / case_folder(c.name));
    write_text_file_atomic((dir / "report" / case_folder(c.name) / "explain_1_2_s0.txt").string(), c.name + "\n");
  }
  write_text_file_atomic((dir / "results.csv").string(), csv);
  write_run_outputs(dir.string(), info, records);
}

TEST(Merge, ShardsMergeIntoTheWholeRunsOutputs) {
  const ScratchDir scratch_merge("merge");
  const fs::path& root = scratch_merge.path();
  const auto records = sample_records();
  write_shard(root / "whole", sample_info(), records);
  for (uint32_t shard = 0; shard < 3; ++shard) {
    std::vector<CaseRecord> part;
    for (size_t i = shard; i < records.size(); i += 3) part.push_back(records[i]);
    write_shard(root / ("shard" + std::to_string(shard)), sample_info(), part);
  }
  const MergeResult merged = merge_conformance_outputs(
      (root / "merged").string(), {(root / "shard2").string(), (root / "shard0").string(), (root / "shard1").string()});
  EXPECT_EQ(merged.exit_code, 1);
  for (const char* file : {"summary.json", "failures.csv", "junit.xml", "results.csv", "report/index.html"})
    EXPECT_EQ(read_text_file((root / "merged" / file).string()), read_text_file((root / "whole" / file).string()))
        << file;
  for (const CaseRecord& c : records) {
    const std::string page = "report/" + case_folder(c.name) + "/index.html";
    EXPECT_EQ(read_text_file((root / "merged" / page).string()), read_text_file((root / "whole" / page).string()))
        << page;
  }
  EXPECT_EQ(read_text_file((root / "merged/report" / case_folder("rastercmp.g.lost") / "explain_1_2_s0.txt").string()),
            "rastercmp.g.lost\n");
}

TEST(Merge, RejectsOverlappingShardsAndOtherDevices) {
  const ScratchDir scratch_merge_bad("merge_bad");
  const fs::path& root = scratch_merge_bad.path();
  const auto records = sample_records();
  write_shard(root / "a", sample_info(), {records[0], records[1]});
  write_shard(root / "b", sample_info(), {records[1]});
  EXPECT_THROW(merge_conformance_outputs((root / "out").string(), {(root / "a").string(), (root / "b").string()}),
               InputError);
  RunInfo other = sample_info();
  other.device = "another GPU";
  write_shard(root / "c", other, {records[2]});
  EXPECT_THROW(merge_conformance_outputs((root / "out").string(), {(root / "a").string(), (root / "c").string()}),
               InputError);
  EXPECT_THROW(merge_conformance_outputs((root / "out").string(), {(root / "missing").string()}), InputError);
}

TEST(Merge, AResumedRunCompletesAnInterruptedOne) {
  const ScratchDir scratch_merge_resume("merge_resume");
  const fs::path& root = scratch_merge_resume.path();
  auto records = sample_records();
  records.resize(2);
  RunInfo interrupted = sample_info();
  interrupted.complete = false;
  interrupted.interrupted = true;
  interrupted.not_run = {records[1].name};
  write_shard(root / "first", interrupted, {records[0]});
  write_shard(root / "rest", sample_info(), {records[1]});
  const MergeResult merged =
      merge_conformance_outputs((root / "out").string(), {(root / "first").string(), (root / "rest").string()});
  EXPECT_FALSE(merged.info.interrupted);
  EXPECT_TRUE(merged.info.not_run.empty());
  EXPECT_EQ(read_text_file((root / "out/summary.json").string()), summary_json(sample_info(), records));
}

}  // namespace
}  // namespace rastercmp
