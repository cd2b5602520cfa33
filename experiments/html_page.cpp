#include "experiments/html_page.hpp"

#include <filesystem>
#include <stdexcept>

#include <kainjow/mustache.hpp>

#include "experiments/page_template.hpp"

#include "model/image_io.hpp"

namespace rastercmp::experiments {

namespace {

using kainjow::mustache::data;
using kainjow::mustache::mustache;

data string_list(const std::vector<std::string>& items) {
  data list{data::type::list};
  for (const std::string& item : items) list << data(item);
  return list;
}

data section_data(const PageSection& section) {
  data d;
  d.set("heading", section.heading);
  d.set("text", section.text);
  d.set("has_table", !section.table.empty());
  if (!section.table.empty()) {
    d.set("header", string_list(section.table.front()));
    data rows{data::type::list};
    for (size_t r = 1; r < section.table.size(); ++r) {
      data row;
      row.set("cells", string_list(section.table[r]));
      rows << row;
    }
    d.set("rows", rows);
  }
  data charts{data::type::list};
  for (const std::string& chart : section.charts) {
    data c;
    c.set("name", chart);
    charts << c;
  }
  d.set("charts", charts);
  return d;
}

}  // namespace

std::string index_html(const std::string& title, const std::vector<PageSection>& sections,
                       const std::vector<std::string>& raw_files) {
  data page;
  page.set("title", title);
  data list{data::type::list};
  for (const PageSection& section : sections) list << section_data(section);
  page.set("sections", list);
  page.set("raw_files", string_list(raw_files));
  mustache view{std::string(experiment_page_template())};
  if (!view.is_valid()) throw std::logic_error("experiment page template: " + view.error_message());
  return view.render(page);  // {{...}} escapes &, <, >, " and '
}

void write_index_html(const std::string& dir, const std::string& title, const std::vector<PageSection>& sections,
                      const std::vector<std::string>& raw_files) {
  write_text_file_atomic((std::filesystem::path(dir) / "index.html").string(), index_html(title, sections, raw_files));
}

}  // namespace rastercmp::experiments
