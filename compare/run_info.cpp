#include "compare/run_info.hpp"

#include <algorithm>

namespace rastercmp {

std::map<std::string, size_t> count_statuses(const std::vector<CaseRecord>& records) {
  std::map<std::string, size_t> counts;
  for (const CaseRecord& c : records) ++counts[c.status];
  return counts;
}

bool run_passed(const RunInfo& info, const std::vector<CaseRecord>& records) {
  return info.complete && !info.interrupted && info.not_run.empty() && info.missing_unnamed == 0 &&
         std::none_of(records.begin(), records.end(), [](const CaseRecord& c) { return c.fails_run; });
}

}  // namespace rastercmp
