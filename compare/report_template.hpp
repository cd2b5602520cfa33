// The HTML report's mustache templates and style sheet (compare/templates/), embedded in the
// binary at configure time (compare/CMakeLists.txt), so the report never needs the source tree.
#pragma once

#include <string_view>

namespace rastercmp {

std::string_view report_template();       // index.html: summary and case table
std::string_view case_template();         // cases/<case>/index.html: one case
std::string_view bad_samples_template();  // cases/<case>/bad-samples-<n>.html: the full bad-sample list
std::string_view report_css();            // style.css

}  // namespace rastercmp
