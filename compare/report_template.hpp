// The HTML report's mustache template (compare/templates/report.html.mustache), embedded in the
// binary at configure time (compare/CMakeLists.txt), so the report never needs the source tree.
#pragma once

#include <string_view>

namespace rastercmp {

std::string_view report_template();

}  // namespace rastercmp
