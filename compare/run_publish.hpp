// A conformance run's outputs as a whole: the machine-readable files (compare/run_outputs.hpp)
// and the HTML report (compare/report.hpp), rewritten together after every case.
#pragma once

#include <string>
#include <vector>

#include "compare/case_record.hpp"
#include "compare/run_info.hpp"

namespace rastercmp {

// Rewrites failures.csv, junit.xml, summary.json and report/index.html in `out_dir`.
void write_run_outputs(const std::string& out_dir, const RunInfo& info, const std::vector<CaseRecord>& records);

}  // namespace rastercmp
