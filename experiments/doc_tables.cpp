#include "experiments/doc_tables.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

#include <fmt/core.h>

#include "model/errors.hpp"
#include "model/file_read.hpp"
#include "model/image_io.hpp"

namespace rastercmp::experiments {
namespace fs = std::filesystem;
namespace {

constexpr const char* kColumnsPrefix = "<!-- columns:";
constexpr const char* kBeginPrefix = "<!-- table:";
constexpr const char* kEndPrefix = "<!-- end table:";
constexpr const char* kMarkerForm = "`<!-- table: NAME from: rastercmp ARGS -->`";

std::string trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const size_t e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// The document's lines without their '\n' (a last line without one included).
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < text.size()) {
    const size_t nl = text.find('\n', start);
    if (nl == std::string::npos) {
      lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, nl - start));
    start = nl + 1;
  }
  return lines;
}

std::string at_line(const std::string& file, size_t line) { return fmt::format("{}:{}: ", file, line); }

// "| a | b |" → {"a", "b"}; nullopt when the line is not a table row.
std::optional<std::vector<std::string>> table_cells(const std::string& raw) {
  const std::string line = trim(raw);
  if (line.size() < 2 || line.front() != '|' || line.back() != '|') return std::nullopt;
  std::vector<std::string> cells;
  size_t start = 1;
  for (size_t i = 1; i < line.size(); ++i) {
    if (line[i] != '|') continue;
    cells.push_back(trim(line.substr(start, i - start)));
    start = i + 1;
  }
  return cells;
}

bool is_separator(const std::vector<std::string>& cells) {
  for (const std::string& c : cells)
    if (c.empty() || c.find_first_not_of("-:") != std::string::npos) return false;
  return !cells.empty();
}

MarkdownTable parse_table_lines(const std::vector<std::string>& lines, size_t first_line, const std::string& file) {
  MarkdownTable table;
  size_t row_line = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (trim(lines[i]).empty()) continue;
    const auto cells = table_cells(lines[i]);
    const std::string where = at_line(file, first_line + i);
    if (!cells) throw UsageError(where + "expected a markdown table row `| ... |`, found `" + trim(lines[i]) + "`");
    if (row_line == 0) {
      table.header = *cells;
    } else if (row_line == 1) {
      if (!is_separator(*cells) || cells->size() != table.header.size())
        throw UsageError(where + fmt::format("expected the separator row of {} columns `|---|...|`", table.header.size()));
    } else {
      if (cells->size() != table.header.size())
        throw UsageError(where + fmt::format("expected {} cells as in the header, found {}", table.header.size(),
                                             cells->size()));
      table.rows.push_back(*cells);
    }
    ++row_line;
  }
  if (row_line < 2) throw UsageError(at_line(file, first_line) + "expected a markdown table (header and separator)");
  return table;
}

std::string kind_text(const ColumnSpec& c) {
  switch (c.kind) {
    case ColumnKind::Exact: return "exact";
    case ColumnKind::Host: return "host";
    case ColumnKind::Timed: return "timed within " + c.interval_column;
  }
  return "exact";
}

// "**1.589**", "40,42" → the number; nullopt when the cell holds none.
std::optional<double> cell_number(const std::string& cell) {
  std::string s;
  for (char ch : cell)
    if (ch != '*' && ch != ',') s += ch;
  s = trim(s);
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || trim(end).size() != 0 || !std::isfinite(v)) return std::nullopt;
  return v;
}

// "lo .. hi" → {lo, hi}.
std::optional<std::pair<double, double>> cell_interval(const std::string& cell) {
  const size_t dots = cell.find("..");
  if (dots == std::string::npos) return std::nullopt;
  const auto lo = cell_number(cell.substr(0, dots)), hi = cell_number(cell.substr(dots + 2));
  if (!lo || !hi) return std::nullopt;
  return std::make_pair(std::min(*lo, *hi), std::max(*lo, *hi));
}

// A row's name in a drift report: its leading cells until no other row starts the same way.
std::string row_label(const MarkdownTable& t, size_t r) {
  const size_t width = t.header.size();
  for (size_t n = 1; n <= std::min<size_t>(width, 3); ++n) {
    bool unique = true;
    for (size_t o = 0; o < t.rows.size() && unique; ++o)
      if (o != r && std::equal(t.rows[o].begin(), t.rows[o].begin() + n, t.rows[r].begin())) unique = false;
    if (unique || n == std::min<size_t>(width, 3)) {
      std::string label;
      for (size_t c = 0; c < n; ++c) label += (c ? " | " : "") + t.rows[r][c];
      return fmt::format("row {} ({})", r + 1, label);
    }
  }
  return fmt::format("row {}", r + 1);
}

}  // namespace

std::string render_markdown(const MarkdownTable& table) {
  auto row = [](const std::vector<std::string>& cells) {
    std::string line = "|";
    for (const std::string& c : cells) line += " " + c + " |";
    return line + "\n";
  };
  std::string text = row(table.header) + "|";
  for (size_t i = 0; i < table.header.size(); ++i) text += "---|";
  text += "\n";
  for (const auto& r : table.rows) text += row(r);
  return text;
}

std::string table_file_text(const MarkdownTable& table) {
  std::string kinds;
  for (size_t i = 0; i < table.columns.size(); ++i) kinds += (i ? " | " : "") + kind_text(table.columns[i]);
  return std::string(kColumnsPrefix) + " " + kinds + " -->\n" + render_markdown(table);
}

void write_markdown_table(const std::string& out_dir, const std::string& name, const MarkdownTable& table) {
  if (table.columns.size() != table.header.size())
    throw std::logic_error("table " + name + ": a column kind per header cell is required");
  for (const auto& r : table.rows)
    if (r.size() != table.header.size()) throw std::logic_error("table " + name + ": a row of another width");
  const fs::path dir = fs::path(out_dir) / "tables";
  fs::create_directories(dir);
  write_text_file_atomic((dir / (name + ".md")).string(), table_file_text(table));
}

MarkdownTable parse_table_file(const std::string& text, const std::string& file) {
  std::vector<std::string> lines = split_lines(text);
  if (lines.empty() || !starts_with(lines[0], kColumnsPrefix) || trim(lines[0]).size() < 4 ||
      trim(lines[0]).substr(trim(lines[0]).size() - 3) != "-->")
    throw UsageError(at_line(file, 1) + "expected `<!-- columns: KIND | ... -->` (exact, host or timed within COLUMN)");
  const std::string first = trim(lines[0]);
  const std::string spec = first.substr(std::string(kColumnsPrefix).size(),
                                        first.size() - 3 - std::string(kColumnsPrefix).size());
  MarkdownTable table = parse_table_lines({lines.begin() + 1, lines.end()}, 2, file);
  size_t start = 0;
  for (;;) {
    const size_t bar = spec.find('|', start);
    const std::string k = trim(spec.substr(start, bar == std::string::npos ? std::string::npos : bar - start));
    if (k == "exact") {
      table.columns.push_back({ColumnKind::Exact, ""});
    } else if (k == "host") {
      table.columns.push_back({ColumnKind::Host, ""});
    } else if (starts_with(k, "timed within ")) {
      const std::string interval = trim(k.substr(13));
      if (std::find(table.header.begin(), table.header.end(), interval) == table.header.end())
        throw UsageError(at_line(file, 1) + "expected the interval column `" + interval + "` in the header");
      table.columns.push_back({ColumnKind::Timed, interval});
    } else {
      throw UsageError(at_line(file, 1) + "expected exact, host or `timed within COLUMN`, found `" + k + "`");
    }
    if (bar == std::string::npos) break;
    start = bar + 1;
  }
  if (table.columns.size() != table.header.size())
    throw UsageError(at_line(file, 1) + fmt::format("expected {} column kinds, found {}", table.header.size(),
                                                    table.columns.size()));
  return table;
}

MarkdownTable read_table_file(const std::string& path) {
  return parse_table_file(read_bounded_file(path, 1u << 20, "a table a command wrote"), path);
}

std::vector<DocMarker> parse_doc_markers(const std::string& text, const std::string& file) {
  const std::vector<std::string> lines = split_lines(text);
  std::vector<DocMarker> markers;
  std::set<std::string> names;
  std::optional<DocMarker> open;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string line = trim(lines[i]);
    const std::string where = at_line(file, i + 1);
    if (starts_with(line, kBeginPrefix)) {
      if (open)
        throw UsageError(where + fmt::format("expected `<!-- end table: {} -->` (opened on line {}) before another table",
                                             open->name, open->begin_line));
      const size_t from = line.find(" from: ");
      if (from == std::string::npos || line.size() < 4 || line.substr(line.size() - 3) != "-->")
        throw UsageError(where + "malformed marker: expected " + kMarkerForm + ", found `" + line + "`");
      DocMarker m;
      m.name = trim(line.substr(std::string(kBeginPrefix).size(), from - std::string(kBeginPrefix).size()));
      m.command = trim(line.substr(from + 7, line.size() - 3 - (from + 7)));
      m.begin_line = i + 1;
      m.indent = lines[i].substr(0, lines[i].find_first_not_of(" \t"));
      if (m.name.empty() || m.name.find_first_of(" \t/") != std::string::npos)
        throw UsageError(where + "malformed marker: expected a table name without blanks or '/' in " + kMarkerForm);
      if (!starts_with(m.command, "rastercmp "))
        throw UsageError(where + "malformed marker: expected the command to start with `rastercmp ` in " + kMarkerForm);
      if (!names.insert(m.name).second) throw UsageError(where + "table `" + m.name + "` is embedded twice");
      open = m;
    } else if (starts_with(line, kEndPrefix)) {
      const std::string name =
          line.size() >= std::string(kEndPrefix).size() + 3 && line.substr(line.size() - 3) == "-->"
              ? trim(line.substr(std::string(kEndPrefix).size(), line.size() - 3 - std::string(kEndPrefix).size()))
              : std::string();
      if (!open) throw UsageError(where + "expected " + kMarkerForm + " before `" + line + "`");
      if (name != open->name)
        throw UsageError(where + fmt::format("expected `<!-- end table: {} -->` (opened on line {}), found `{}`",
                                             open->name, open->begin_line, line));
      open->end_line = i + 1;
      markers.push_back(*open);
      open.reset();
    } else if (starts_with(line, "<!-- table") || starts_with(line, "<!-- end table")) {
      throw UsageError(where + "malformed marker: expected " + kMarkerForm + " or `<!-- end table: NAME -->`");
    }
  }
  if (open)
    throw UsageError(at_line(file, open->begin_line) +
                     fmt::format("expected `<!-- end table: {} -->` after this marker, found the end of the file",
                                 open->name));
  return markers;
}

MarkdownTable documented_table(const std::string& text, const DocMarker& marker, const std::string& file) {
  const std::vector<std::string> lines = split_lines(text);
  return parse_table_lines({lines.begin() + marker.begin_line, lines.begin() + (marker.end_line - 1)},
                           marker.begin_line + 1, file);
}

size_t add_doc_command(std::vector<DocCommand>& commands, const std::string& command, const std::string& where) {
  const std::string text = trim(command);
  if (!starts_with(text, "rastercmp "))
    throw UsageError(where + "expected a command that starts with `rastercmp `, found `" + text + "`");
  // Split into words, a `{...}` group (nested braces allowed) being one word.
  std::vector<std::string> words;
  std::string word;
  int depth = 0;
  for (char ch : text.substr(10)) {
    if (ch == '{') ++depth;
    if (ch == '}' && --depth < 0) throw UsageError(where + "expected `{` before `}` in `" + text + "`");
    if ((ch == ' ' || ch == '\t') && depth == 0) {
      if (!word.empty()) words.push_back(word);
      word.clear();
    } else {
      word += ch;
    }
  }
  if (depth != 0) throw UsageError(where + "expected `}` to close `{` in `" + text + "`");
  if (!word.empty()) words.push_back(word);
  DocCommand c;
  for (const std::string& w : words) {
    if (w.front() == '{') {
      if (w.back() != '}') throw UsageError(where + "expected `{ARGS}` as one argument, found `" + w + "`");
      const size_t dep = add_doc_command(commands, "rastercmp " + w.substr(1, w.size() - 2), where);
      c.args.push_back("");
      c.dependencies.push_back(dep + 1);
      c.key += " {" + commands[dep].key + "}";
    } else {
      if (w == "--out") throw UsageError(where + "expected no --out in `" + text + "` (the tool chooses the folder)");
      c.args.push_back(w);
      c.dependencies.push_back(0);
      c.key += " " + w;
    }
  }
  c.key = "rastercmp" + c.key;
  for (size_t i = 0; i < commands.size(); ++i)
    if (commands[i].key == c.key) return i;
  commands.push_back(c);
  return commands.size() - 1;
}

std::vector<CellDrift> compare_tables(const std::string& name, const MarkdownTable& documented,
                                      const MarkdownTable& measured) {
  std::vector<CellDrift> drifts;
  if (documented.header != measured.header) {
    auto join = [](const std::vector<std::string>& cells) {
      std::string s;
      for (const auto& c : cells) s += (s.empty() ? "" : " | ") + c;
      return s;
    };
    drifts.push_back({name, "header", "(all)", join(documented.header), join(measured.header), false});
    return drifts;
  }
  if (documented.rows.size() != measured.rows.size())
    drifts.push_back({name, "rows", "(count)", std::to_string(documented.rows.size()),
                      std::to_string(measured.rows.size()), false});
  const size_t rows = std::min(documented.rows.size(), measured.rows.size());
  for (size_t r = 0; r < rows; ++r) {
    for (size_t c = 0; c < measured.header.size(); ++c) {
      const std::string& doc = documented.rows[r][c];
      const std::string& got = measured.rows[r][c];
      const ColumnSpec spec = c < measured.columns.size() ? measured.columns[c] : ColumnSpec{};
      if (spec.kind == ColumnKind::Host) continue;
      if (spec.kind == ColumnKind::Exact) {
        if (doc != got) drifts.push_back({name, row_label(measured, r), measured.header[c], doc, got, false});
        continue;
      }
      const size_t ic = static_cast<size_t>(
          std::find(measured.header.begin(), measured.header.end(), spec.interval_column) - measured.header.begin());
      const auto interval = ic < measured.header.size() ? cell_interval(measured.rows[r][ic]) : std::nullopt;
      const auto value = cell_number(doc);
      if (!interval) {
        // No interval measured (a value that could not be timed): the cells must agree as text.
        if (doc != got) drifts.push_back({name, row_label(measured, r), measured.header[c], doc, got, true});
        continue;
      }
      // Two runs are told apart only where their intervals are disjoint (as the speed-accuracy front
      // marks points "not separated"): one run's interval of the median leaves out the run-to-run
      // spread that the host's state adds (frequency, cache placement), about 1 % on an idle host.
      // A documented cell without its interval is held to the new run's interval alone.
      const auto [low, high] = *interval;
      std::optional<std::pair<double, double>> documented_interval;
      if (ic < documented.rows[r].size()) documented_interval = cell_interval(documented.rows[r][ic]);
      bool separated = !value || *value < low || *value > high;
      if (documented_interval) separated = documented_interval->second < low || documented_interval->first > high;
      if (!value || separated)
        drifts.push_back({name, row_label(measured, r), measured.header[c], doc,
                          got + " (" + spec.interval_column + " " + measured.rows[r][ic] + ")", true});
    }
  }
  return drifts;
}

std::string rewrite_doc(const std::string& text, const std::vector<DocMarker>& markers,
                        const std::map<std::string, MarkdownTable>& tables, const std::string& file) {
  // Byte offsets of each line's start, so that everything outside the tables is copied as it is.
  std::vector<size_t> line_start = {0};
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') line_start.push_back(i + 1);
  std::string out;
  size_t copied = 0;
  for (const DocMarker& m : markers) {
    const auto it = tables.find(m.name);
    if (it == tables.end()) throw UsageError(at_line(file, m.begin_line) + "no measured table `" + m.name + "`");
    const size_t begin = line_start[m.begin_line];    // the line after the begin marker
    const size_t end = line_start[m.end_line - 1];    // the end marker's line
    out += text.substr(copied, begin - copied);
    for (const std::string& line : split_lines(render_markdown(it->second))) out += m.indent + line + "\n";
    copied = end;
  }
  out += text.substr(copied);
  return out;
}

MarkdownTable measured_table(const std::string& out_dir, const DocMarker& marker, const std::string& file) {
  const fs::path path = fs::path(out_dir) / "tables" / (marker.name + ".md");
  if (!fs::exists(path)) {
    std::vector<std::string> names;
    if (fs::is_directory(fs::path(out_dir) / "tables"))
      for (const auto& e : fs::directory_iterator(fs::path(out_dir) / "tables"))
        if (e.path().extension() == ".md") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw UsageError(at_line(file, marker.begin_line) +
                     fmt::format("unknown table `{}`: `{}` writes {}", marker.name, marker.command,
                                 list.empty() ? std::string("no table") : list));
  }
  return read_table_file(path.string());
}

}  // namespace rastercmp::experiments
