// The index.html of an experiment folder: each chart shown (SVG, linking its PNG), then the raw
// files. Rendered from experiments/templates/experiment_page.html.mustache (kainjow mustache, as
// the report), written atomically.
#pragma once

#include <string>
#include <vector>

namespace rastercmp::experiments {

struct PageSection {
  std::string heading;
  std::string text;                                  // one paragraph, plain text (escaped)
  std::vector<std::string> charts;                   // chart names (NAME.svg / NAME.png)
  std::vector<std::vector<std::string>> table = {};  // optional: first row is the header (plain text, escaped)
};

std::string index_html(const std::string& title, const std::vector<PageSection>& sections,
                       const std::vector<std::string>& raw_files);
void write_index_html(const std::string& dir, const std::string& title, const std::vector<PageSection>& sections,
                      const std::vector<std::string>& raw_files);

}  // namespace rastercmp::experiments
