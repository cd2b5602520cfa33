// The experiment pages' mustache template (experiments/templates/experiment_page.html.mustache),
// embedded in the binary at configure time (experiments/CMakeLists.txt), as the report's is.
#pragma once

#include <string_view>

namespace rastercmp::experiments {

std::string_view experiment_page_template();

}  // namespace rastercmp::experiments
