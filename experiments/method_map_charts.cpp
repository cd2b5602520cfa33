// Charts and page sections of the method maps (method_maps.hpp), from stability.csv read back: one
// chart per experiment (map_<experiment>), one panel per case, one line per method of the family
// (the same line type for a method on every panel), and the table of failure boundaries.
#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "experiments/failure_boundary.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/method_maps.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {
namespace {

size_t method_style(std::string_view family, const std::string& method) {
  const std::vector<NamedMethod> methods = family_methods(family);
  for (size_t i = 0; i < methods.size(); ++i)
    if (methods[i].first == method) return i + 1;
  return methods.size() + 1;
}

// One panel: all parameters positive -> a log axis of the values; otherwise (0, negative w) the
// values in plan order as categories, benign on the left.
std::string panel(const CsvTable& table, const MapExperiment& e, const std::string& case_name,
                  std::vector<DataBlock>& blocks) {
  const std::string experiment(e.name);
  const Where where{{"experiment", experiment}, {"case", case_name}};
  const std::vector<std::string> params = distinct(table, "param_a", where);
  bool positive = true;
  for (const std::string& p : params) positive = positive && to_double(p) > 0;
  const size_t param = table.column("param_a");
  std::string plot = "plot ";
  for (const std::string& method : distinct(table, "method", where)) {
    DataBlock block{method, {{"\"" + method + "\"", "x"}}};
    for (const Row& row : select_rows(table, {{"experiment", experiment}, {"case", case_name}, {"method", method}})) {
      const double measure = map_measure(table, row, std::string(e.measure));
      if (std::isnan(measure)) continue;  // refused: no point
      size_t index = 0;
      while (params[index] != row[param]) ++index;
      block.rows.push_back({positive ? row[param] : std::to_string(index), num(measure)});
    }
    if (block.rows.empty()) block.rows.push_back({"NaN", "NaN"});
    plot += fmt::format("DATA index {} using 1:2 title {} with linespoints lt {}, ", blocks.size(), gp_quote(method),
                        method_style(e.family, method));
    blocks.push_back(block);
  }
  plot.resize(plot.size() - 2);
  std::string axis;
  if (positive) {
    axis = "set logscale x 10\nset format x '10^{%L}'\nunset xtics\nset xtics\n";
    // Benign on the left: a descending sweep gets a reversed axis (explicit bounds, half a step out).
    double low = to_double(params.front()), high = low;
    for (const std::string& p : params) low = std::min(low, to_double(p)), high = std::max(high, to_double(p));
    const std::vector<Row> first = select_rows(table, {{"experiment", experiment}, {"case", case_name},
                                                       {"method", distinct(table, "method", where).front()}});
    const bool descending = to_double(first.front()[param]) > to_double(first.back()[param]);
    axis += descending ? fmt::format("set xrange [{:g}:{:g}]\n", high * 1.5, low / 1.5)
                       : fmt::format("set xrange [{:g}:{:g}]\n", low / 1.5, high * 1.5);
  } else {
    axis = "unset logscale x\nset format x '%g'\nset xtics (";
    for (size_t i = 0; i < params.size(); ++i) axis += (i ? ", " : "") + gp_quote(params[i]) + " " + std::to_string(i);
    axis += ") rotate by -30\nset xrange [-0.5:" + std::to_string(params.size()) + "-0.5] noreverse\n";
  }
  const std::string y = e.measure == "value_cpu" ? "set yrange [-0.02:1.02]\nset ylabel 'fraction won by the wrong surface'\n"
                                                 : "set yrange [-0.5:1<*]\nset ylabel 'samples whose owner or depth differs from the reference'\n";
  return "set title " + gp_quote(case_name) + "\n" + axis + y + plot + "\n";
}

void chart(const std::string& dir, const CsvTable& table, const MapExperiment& e) {
  const std::vector<std::string> cases = distinct(table, "case", {{"experiment", std::string(e.name)}});
  if (cases.empty()) return;
  std::vector<DataBlock> blocks;
  const size_t columns = cases.size() < 2 ? 1 : cases.size() < 5 ? 2 : 3;
  std::string body = "set xlabel " + gp_quote(std::string(e.parameter)) + "\nset key left center font ',9'\nset grid\n";
  body += fmt::format("set multiplot layout {},{} title {} noenhanced\n", (cases.size() + columns - 1) / columns, columns,
                      gp_quote(std::string(e.family) + ": " + std::string(e.notes)));
  for (const std::string& c : cases) body += panel(table, e, c, blocks);
  body += "unset multiplot\n";
  render_chart(dir, "map_" + std::string(e.name), blocks, body);
}

std::string text(double value) { return std::isnan(value) ? "-" : num(value); }

}  // namespace

std::vector<PageSection> write_method_map_charts(const std::string& dir, const CsvTable& table) {
  std::vector<PageSection> sections;
  const std::vector<FailureBoundary> boundaries = failure_boundaries(table);
  for (const MapExperiment& e : method_map_experiments()) {
    chart(dir, table, e);
    PageSection section{std::string(e.family) + ": " + std::string(e.name),
                        std::string(e.notes) + ". Parameter: " + std::string(e.parameter) +
                            ", from the benign end to the hard end. Boundary: the first value at which " +
                            (e.measure == "value_cpu" ? "the method's own wrong surface wins a pixel"
                                                      : "a sample's owner or depth differs from lavapipe") +
                            "; the true boundary lies after the last clean value.",
                        {"map_" + std::string(e.name)},
                        {{"case", "method", "last clean", "boundary", "failing points", "refused points"}}};
    for (const FailureBoundary& b : boundaries)
      if (b.experiment == e.name)
        section.table.push_back({b.case_name, b.method, text(b.last_clean), text(b.boundary),
                                 std::to_string(b.failing) + " of " + std::to_string(b.points),
                                 std::to_string(b.refused)});
    if (section.table.size() > 1) sections.push_back(section);
  }
  return sections;
}

}  // namespace rastercmp::experiments
