// The machine-readable outputs of a conformance run (deqp-runner conventions, compare/expectations.hpp):
//   results.csv   name,status,duration   every case in run order, then `name,Missing,0.000` for each
//                                        case without a result (not run yet, or never)
//   failures.csv  name,status            every case whose status fails the run, Missing included,
//                                        sorted by name: the next --baseline
//   junit.xml     one <testcase> per case, with durations; a Missing case is a <failure>
//   summary.json  "complete" (true only once the run has finished), "interrupted", "not_run",
//                 "passed", counts and per-case records; deterministic: no durations, no timestamps
// All are rewritten whole through a temporary file and a rename, so at any moment each is a whole
// file, and a run that has not finished (or was killed) reads as not passed.
#pragma once

#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "compare/case_record.hpp"
#include "compare/run_info.hpp"

namespace rastercmp {

std::string results_csv_line(const CaseRecord& record);
std::string results_csv(const RunInfo& info, const std::vector<CaseRecord>& records);
// name → duration in seconds. Throws InputError for a malformed line.
std::map<std::string, double> parse_results_csv(std::string_view text, const std::string& file);

std::string failures_csv(const RunInfo& info, const std::vector<CaseRecord>& records);
std::string junit_xml(const RunInfo& info, const std::vector<CaseRecord>& records);
std::string summary_json(const RunInfo& info, const std::vector<CaseRecord>& records);

struct ParsedSummary {
  RunInfo info;
  std::vector<CaseRecord> records;  // durations 0: they live in results.csv
};
ParsedSummary parse_summary_json(std::string_view text, const std::string& file);

// Rewrites results.csv, failures.csv, junit.xml and summary.json in `out_dir` (the report: compare/run_publish.hpp).
void write_run_files(const std::string& out_dir, const RunInfo& info, const std::vector<CaseRecord>& records);

}  // namespace rastercmp
