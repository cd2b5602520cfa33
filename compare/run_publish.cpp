#include "compare/run_publish.hpp"

#include <filesystem>

#include "compare/report.hpp"
#include "compare/run_outputs.hpp"

namespace rastercmp {

void write_run_outputs(const std::string& out_dir, const RunInfo& info, const std::vector<CaseRecord>& records) {
  write_run_files(out_dir, info, records);
  write_report_html((std::filesystem::path(out_dir) / "report").string(), info, records);
}

}  // namespace rastercmp
