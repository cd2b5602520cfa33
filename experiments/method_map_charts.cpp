// Charts and page sections of the method maps (method_maps.hpp), from stability.csv read back: one
// chart per experiment (map_<experiment>), one panel per case, one line per method of the family
// (the same line type for a method on every panel), and the table of failure boundaries.
#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "experiments/failure_boundary.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/map_theory.hpp"
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

// One panel: a linear axis where the experiment asks for one (angles); else all parameters positive -> a log axis of
// the values; otherwise (0, negative w) a symmetric log axis (SymlogAxis), 0 at its tic: every point at its real value,
// benign on the left. A refused point (not_supported) is a star in the method's colour along the top of the panel; a
// predicted boundary (predicted_boundary) a dotted vertical line in the method's colour; a series'
// per-point expectation (method_map_expectation) open squares along the bottom where theory says it
// differs (diamonds: a tie, either way), open triangles along the top where it says it refuses, and
// its marked value (cull: edge-on) a dashed line.
// shared_key: many panels (depth_far_near's twelve); the first panel's legend stands for all, at
// the outer right of the chart, the others have none, and predicted lines are titled without their
// value (it is in the table and stability.json).
std::string panel(const CsvTable& table, const std::vector<FailureBoundary>& boundaries, const MapExperiment& e,
                  const std::string& case_name, std::vector<DataBlock>& blocks, bool shared_key, bool first_panel) {
  const std::string experiment(e.name);
  const Where where{{"experiment", experiment}, {"case", case_name}};
  const std::vector<std::string> params = distinct(table, "param_a", where);
  std::vector<double> values;
  bool positive = true;
  for (const std::string& p : params) {
    values.push_back(to_double(p));
    positive = positive && to_double(p) > 0;
  }
  const SymlogAxis symlog(values);
  const bool linear = e.linear_axis;
  const auto x_of = [&](double v) {
    return positive || linear ? fmt::format("{:.10g}", v) : fmt::format("{:.10g}", symlog.position(v));
  };
  const size_t param = table.column("param_a"), agree = table.column("cpu_vk_agree");
  const std::vector<std::string> methods = distinct(table, "method", where);
  // The fill maps chart the samples whose owner differs, the count the coverage model predicts (their
  // triangles are flat, so depth differs only where coverage does: the boundaries are the same).
  const std::string chart_measure = e.family == "fill" ? "coverage_mismatch" : std::string(e.measure);
  std::string plot = "plot ", marks;
  for (size_t k = 0; k < methods.size(); ++k) {
    const std::string& method = methods[k];
    const size_t style = method_style(e.family, method);
    DataBlock block{method, {{"\"" + method + "\"", "x"}}}, refused{method + " refused", {{"\"" + method + " refused\"", "x"}}};
    for (const Row& row : select_rows(table, {{"experiment", experiment}, {"case", case_name}, {"method", method}})) {
      if (row[agree] == "not_supported") {
        refused.rows.push_back({x_of(to_double(row[param])), fmt::format("{:g}", 0.97 - 0.035 * double(k))});
        continue;
      }
      const double measure = map_measure(table, row, chart_measure);
      if (std::isnan(measure)) continue;
      block.rows.push_back({x_of(to_double(row[param])), num(measure)});
    }
    if (block.rows.size() == 1) block.rows.push_back({"NaN", "NaN"});
    plot += fmt::format("DATA index {} using 1:2 title {} with linespoints lt {}, ", blocks.size(), gp_quote(method), style);
    blocks.push_back(block);
    if (refused.rows.size() > 1) {
      plot += fmt::format("DATA index {} using 1:2 axes x1y2 title {} with points lt {} pt 3 ps 2.5, ", blocks.size(),
                          gp_quote(method + " refused"), style);
      blocks.push_back(refused);
    }
    if (const auto expected = method_map_expectation(experiment, case_name, method)) {
      if (!std::isnan(expected->marked)) {
        marks += fmt::format("set arrow from {}, graph 0 to {}, graph 1 nohead lt {} dt 2 lw 2\n", x_of(expected->marked),
                             x_of(expected->marked), style);
        plot += fmt::format("keyentry with lines lt {} dt 2 lw 2 title {}, ", style,
                            gp_quote(fmt::format("{} {:g}", expected->marked_label, expected->marked)));
      }
      // Theory per point: where it predicts a count, an open circle at that count (a measured point
      // inside its circle agrees); elsewhere its outcome along the top of the panel, an open square
      // where it says the method differs, a diamond where a tie leaves it open, a triangle where it
      // says the method refuses (around the measured refusal's star when they agree).
      const FailureBoundary& b = find_boundary(boundaries, experiment, case_name, method);
      DataBlock counts{method + " theory count", {{"\"" + method + " theory count\"", "x"}}};
      std::vector<DataBlock> outcomes{{method + " theory: differs", {{"\"" + method + " theory: differs\"", "x"}}},
                                      {method + " theory: either", {{"\"" + method + " theory: either\"", "x"}}},
                                      {method + " theory: refused", {{"\"" + method + " theory: refused\"", "x"}}}};
      const std::string strip = fmt::format("{:g}", 0.97 - 0.035 * double(k));  // the refusal stars' row
      for (const PointCheck& c : check_expectation(table, b, *expected)) {
        const Outcome o = c.predicted.outcome;
        if (!std::isnan(c.predicted.coverage_mismatch) && chart_measure == "coverage_mismatch")
          counts.rows.push_back({x_of(c.param), num(c.predicted.coverage_mismatch)});
        else if (o != Outcome::Clean && !(o == Outcome::Either && c.predicted.coverage_mismatch == 0))  // open depth only
          outcomes[o == Outcome::Differs ? 0 : o == Outcome::Either ? 1 : 2].rows.push_back({x_of(c.param), strip});
      }
      if (counts.rows.size() > 1) {
        plot += fmt::format("DATA index {} using 1:2 title {} with points lt {} pt 6 ps 2.4, ", blocks.size(),
                            gp_quote(method + " theory: " + expected->legend), style);
        blocks.push_back(counts);
      }
      constexpr int kOutcomePoint[] = {4, 12, 8};
      for (size_t kind = 0; kind < outcomes.size(); ++kind) {
        if (outcomes[kind].rows.size() == 1) continue;  // the header row alone: theory never says so
        if (outcomes[kind].rows.size() == 2) outcomes[kind].rows.push_back({"NaN", "NaN"});
        plot += fmt::format("DATA index {} using 1:2 axes x1y2 title {} with points lt {} pt {} ps 1.8, ", blocks.size(),
                            gp_quote(shared_key ? outcomes[kind].title : outcomes[kind].title + " (" + expected->legend + ")"),
                            style, kOutcomePoint[kind]);
        blocks.push_back(outcomes[kind]);
      }
    }
    if (const auto prediction = predicted_boundary(experiment, case_name, method)) {
      marks += fmt::format("set arrow from {}, graph 0 to {}, graph 1 nohead lt {} dt 3 lw 2\n", x_of(prediction->value),
                           x_of(prediction->value), style);
      plot += fmt::format("keyentry with lines lt {} dt 3 lw 2 title {}, ", style,
                          gp_quote(shared_key ? method + " predicted (dotted)"
                                              : fmt::format("{} predicted {:.3g}", method, prediction->value)));
    }
  }
  plot.resize(plot.size() - 2);
  std::string axis;
  // Benign on the left: a descending sweep gets a reversed axis (explicit bounds, half a step out).
  const std::vector<Row> first = select_rows(table, {{"experiment", experiment}, {"case", case_name}, {"method", methods.front()}});
  const bool descending = to_double(first.front()[param]) > to_double(first.back()[param]);
  if (linear) {
    double low = values.front(), high = low;
    for (double v : values) low = std::min(low, v), high = std::max(high, v);
    const double pad = (high - low) / 40;
    axis = "unset logscale x\nset format x '%g'\nunset xtics\nset xtics\n" +
           (descending ? fmt::format("set xrange [{:g}:{:g}]\n", high + pad, low - pad)
                       : fmt::format("set xrange [{:g}:{:g}]\n", low - pad, high + pad));
  } else if (positive) {
    axis = "set logscale x 10\nset format x '10^{%L}'\nunset xtics\nset xtics\n";
    double low = values.front(), high = low;
    for (double v : values) low = std::min(low, v), high = std::max(high, v);
    axis += descending ? fmt::format("set xrange [{:g}:{:g}]\n", high * 1.5, low / 1.5)
                       : fmt::format("set xrange [{:g}:{:g}]\n", low / 1.5, high * 1.5);
  } else {
    double low = symlog.position(values.front()), high = low;
    for (double v : values) low = std::min(low, symlog.position(v)), high = std::max(high, symlog.position(v));
    axis = "unset logscale x\nset format x '%g'\n" + symlog.tics_command("x", params) +
           "set xtics rotate by -30\n" +
           (descending ? fmt::format("set xrange [{:g}:{:g}]\n", high + 0.5, low - 0.5)
                       : fmt::format("set xrange [{:g}:{:g}]\n", low - 0.5, high + 0.5));
  }
  const std::string y = e.measure == "value_cpu"
                            ? std::string("set yrange [-0.02:1.02]\nset ylabel '") +
                                  (shared_key ? "wrong fraction" : "fraction won by the wrong surface") + "'\n"
                        : e.family == "fill"              ? "set yrange [-0.5:1<*]\nset ylabel 'samples whose owner differs'\n"
                        : e.measure == "excess_mismatch" ? "set yrange [-0.5:2<*]\nset ylabel 'samples that differ'\n"
                                                         : "set yrange [-0.5:1<*]\nset ylabel 'samples that differ'\n";
  const std::string key = !shared_key ? ""
                          : first_panel
                              ? "set key at screen 0.995, screen 0.9 right top vertical maxrows auto font ',9'\n"
                              : "unset key\n";
  // Headroom above the data for the rows of refusal stars and theory marks (the top quarter).
  const std::string headroom = e.measure == "value_cpu" ? "set offsets 0, 0, 0, 0\n" : "set offsets 0, 0, graph 0.33, 0\n";
  return "set title " + gp_quote(case_name) + "\nunset arrow\nset y2range [0:1]\nunset y2tics\n" + axis + y + headroom + key +
         marks + plot + "\n";
}

void chart(const std::string& dir, const CsvTable& table, const std::vector<FailureBoundary>& boundaries,
           const MapExperiment& e) {
  const std::vector<std::string> cases = distinct(table, "case", {{"experiment", std::string(e.name)}});
  if (cases.empty()) return;
  std::vector<DataBlock> blocks;
  const size_t columns = cases.size() < 2 ? 1 : cases.size() < 5 ? 2 : 3;
  const bool shared_key = cases.size() > 6;
  std::string body = "set xlabel " + gp_quote(std::string(e.parameter)) + "\nset key below font ',9' maxrows 3\nset grid\n";
  body += fmt::format("set multiplot layout {},{} {}title {} noenhanced\n", (cases.size() + columns - 1) / columns,
                      columns, shared_key ? "margins 0.06,0.78,0.08,0.92 spacing 0.06,0.08 " : "",
                      gp_quote(std::string(e.family) + ": " + std::string(e.notes)));
  for (size_t i = 0; i < cases.size(); ++i) {
    // Many panels: the x label only under the bottom row, so each panel title keeps clear of it.
    if (shared_key)
      body += "set xlabel " + gp_quote(i + columns < cases.size() ? "" : std::string(e.parameter)) + "\n";
    body += panel(table, boundaries, e, cases[i], blocks, shared_key, i == 0);
  }
  body += "unset multiplot\n";
  render_chart(dir, "map_" + std::string(e.name), blocks, body);
}

std::string text(double value) { return std::isnan(value) ? "-" : num(value); }

}  // namespace

std::vector<PageSection> write_method_map_charts(const std::string& dir, const CsvTable& table) {
  std::vector<PageSection> sections;
  const std::vector<FailureBoundary> boundaries = failure_boundaries(table);
  for (const MapExperiment& e : method_map_experiments()) {
    chart(dir, table, boundaries, e);
    PageSection section{
        std::string(e.family) + ": " + std::string(e.name),
        std::string(e.notes) + ". Parameter: " + std::string(e.parameter) +
            ", from the benign end to the hard end. Boundary: the first value at which " +
            (e.measure == "value_cpu"         ? "the method's own wrong surface wins a pixel"
             : e.measure == "excess_mismatch" ? "more samples differ from lavapipe than at the benign end"
                                              : "a sample's owner or depth differs from lavapipe") +
            "; the true boundary lies after the last clean value.",
        {"map_" + std::string(e.name)},
        {{"case", "method", "last clean", "boundary", "failing points", "refused points", "as theory says"}}};
    for (const FailureBoundary& b : boundaries)
      if (b.experiment == e.name) {
        std::string theory = "-";
        if (const auto expected = method_map_expectation(b.experiment, b.case_name, b.method)) {
          const std::vector<PointCheck> points = check_expectation(table, b, *expected);
          const size_t agreeing = size_t(std::count_if(points.begin(), points.end(), [](const PointCheck& c) { return c.agrees; }));
          theory = std::to_string(agreeing) + " of " + std::to_string(points.size()) + " points";
        }
        section.table.push_back({b.case_name, b.method, text(b.last_clean), text(b.boundary),
                                 std::to_string(b.failing) + " of " + std::to_string(b.points),
                                 std::to_string(b.refused), theory});
      }
    if (section.table.size() > 1) sections.push_back(section);
  }
  return sections;
}

}  // namespace rastercmp::experiments
