#include "experiments/html_page.hpp"

#include <filesystem>

#include "model/image_io.hpp"

namespace rastercmp::experiments {

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

namespace {

std::string table_html(const std::vector<std::vector<std::string>>& table) {
  if (table.empty()) return "";
  std::string html = "<table>\n";
  for (size_t r = 0; r < table.size(); ++r) {
    const std::string open = r == 0 ? "<th>" : "<td>", close = r == 0 ? "</th>" : "</td>";
    html += "<tr>";
    for (const std::string& text : table[r]) {
      html += open;
      html += html_escape(text);
      html += close;
    }
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

}  // namespace

void write_index_html(const std::string& dir, const std::string& title, const std::vector<PageSection>& sections,
                      const std::vector<std::string>& raw_files) {
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + html_escape(title) +
                     "</title>\n<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;}"
                     "img{max-width:100%;border:1px solid #ccc;}"
                     "table{border-collapse:collapse;}td,th{border:1px solid #ccc;padding:2px "
                     "8px;text-align:left;}</style></head><body>\n<h1>" +
                     html_escape(title) + "</h1>\n";
  for (const PageSection& section : sections) {
    html += "<h2>" + html_escape(section.heading) + "</h2>\n<p>" + html_escape(section.text) + "</p>\n";
    html += table_html(section.table);
    for (const std::string& chart : section.charts)
      html += "<p><a href=\"" + chart + ".png\"><img src=\"" + chart + ".svg\" alt=\"" + html_escape(chart) +
              "\"></a><br><small>" + chart + ": <a href=\"" + chart + ".svg\">SVG</a> <a href=\"" + chart +
              ".png\">PNG</a> <a href=\"" + chart + ".dat\">data</a> <a href=\"" + chart +
              ".gp\">gnuplot script</a></small></p>\n";
  }
  html += "<h2>Raw numbers</h2>\n<ul>\n";
  for (const std::string& file : raw_files) html += "<li><a href=\"" + file + "\">" + file + "</a></li>\n";
  html += "</ul>\n</body></html>\n";
  write_text_file_atomic((std::filesystem::path(dir) / "index.html").string(), html);
}

}  // namespace rastercmp::experiments
