// A finished case → its record: the verdict and diff numbers of the run, judged against the
// expectations (compare/expectations.hpp). Images and explanations are added by the caller.
#pragma once

#include "compare/case_record.hpp"
#include "compare/case_result.hpp"
#include "compare/case_select.hpp"
#include "compare/expectations.hpp"

namespace rastercmp {

CaseRecord make_case_record(const SuiteCase& suite_case, const CaseResult& result, const Expectations& expectations);

}  // namespace rastercmp
