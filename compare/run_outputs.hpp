// The machine-readable outputs of a conformance run (deqp-runner conventions):
//   results.csv   name,status,duration   every case, appended and flushed as each finishes
//   failures.csv  name,Status            every failing case (not KnownFlake): the next baseline
//   junit.xml     one <testcase> per case, with durations
//   summary.json  counts and per-case records; deterministic: no durations, no timestamps
// All but results.csv are rewritten whole through a temporary file and a rename.
#pragma once

#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "compare/case_record.hpp"
#include "compare/run_info.hpp"

namespace rastercmp {

// Appends one line per case and flushes it, so an interrupted run leaves what it finished.
class ResultsCsvWriter {
 public:
  explicit ResultsCsvWriter(const std::string& path);  // truncates; throws InputError
  ~ResultsCsvWriter();
  ResultsCsvWriter(const ResultsCsvWriter&) = delete;
  ResultsCsvWriter& operator=(const ResultsCsvWriter&) = delete;
  void append(const CaseRecord& record);

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

std::string results_csv_line(const CaseRecord& record);
// name → duration in seconds. Throws InputError for a malformed line.
std::map<std::string, double> parse_results_csv(std::string_view text, const std::string& file);

std::string failures_csv(const std::vector<CaseRecord>& records);
std::string junit_xml(const std::vector<CaseRecord>& records);
std::string summary_json(const RunInfo& info, const std::vector<CaseRecord>& records);

struct ParsedSummary {
  RunInfo info;
  std::vector<CaseRecord> records;  // durations 0: they live in results.csv
};
ParsedSummary parse_summary_json(std::string_view text, const std::string& file);

// Rewrites failures.csv, junit.xml and summary.json in `out_dir` (the report: compare/run_publish.hpp).
void write_run_files(const std::string& out_dir, const RunInfo& info, const std::vector<CaseRecord>& records);

}  // namespace rastercmp
