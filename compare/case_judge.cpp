#include "compare/case_judge.hpp"

namespace rastercmp {

CaseRecord make_case_record(const SuiteCase& suite_case, const CaseResult& result, const Expectations& expectations) {
  CaseRecord record;
  record.name = suite_case.name;
  record.source = suite_case.path;
  record.cpu_method = result.cpu_method;
  record.width = suite_case.scene.width;
  record.height = suite_case.scene.height;
  record.verdict = result.verdict;
  record.message = result.message;
  if (result.diff) record.diff = result.diff->summary;
  record.expectation = expectations.expected(suite_case.name);
  record.expectation_reason = expectations.reason(suite_case.name);
  const Outcome outcome = judge_outcome(suite_case.name, result.verdict, expectations);
  record.status = outcome.status;
  record.fails_run = outcome.fails_run;
  return record;
}

}  // namespace rastercmp
