// Charts, JSON and page of `chart speed-accuracy`.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "experiments/chart_labels.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/html_page.hpp"
#include "experiments/speed_accuracy.hpp"

namespace rastercmp::experiments {
namespace {

std::string quoted(const std::string& text) { return "\"" + text + "\""; }

double mismatch_of(const EntrySummary& e, bool coverage) {
  return coverage ? e.coverage_mismatch_pct : e.depth_mismatch_pct;
}

// Families in order of first appearance: one series (colour, point type) each.
std::vector<std::string> families_of(const SpeedAccuracyRun& run) {
  std::vector<std::string> families;
  for (const EntrySummary& e : run.entries)
    if (std::find(families.begin(), families.end(), e.family) == families.end()) families.push_back(e.family);
  return families;
}

// Axes fixed by the data: x (log) spans every time including lavapipe's with a margin; y starts a
// little below 0 so that points at 0 stand clear of the axis, with ticks from 0.
ChartAxes axes_for(const SpeedAccuracyRun& run, bool coverage) {
  double x_min = run.lavapipe.seconds_per_frame, x_max = x_min, y_max = 0;
  for (const EntrySummary& e : run.entries) {
    x_min = std::min(x_min, e.seconds_per_frame);
    x_max = std::max(x_max, e.seconds_per_frame);
    y_max = std::max(y_max, mismatch_of(e, coverage));
  }
  if (y_max <= 0) y_max = 1;
  return ChartAxes{true, x_min / 1.6, x_max * 1.6, -0.06 * y_max, 1.15 * y_max};
}

// A tick step of 1, 2 or 5 times a power of ten that gives at most about six ticks up to `top`.
double tick_step(double top) {
  const double rough = top / 5, decade = std::pow(10.0, std::floor(std::log10(rough)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * decade >= rough) return m * decade;
  return 10 * decade;
}

std::string label_commands(const SpeedAccuracyRun& run, bool coverage, const ChartAxes& axes) {
  std::vector<ChartPoint> points;
  for (size_t i = 0; i < run.entries.size(); ++i)
    points.push_back({run.entries[i].seconds_per_frame, mismatch_of(run.entries[i], coverage), int(i + 1)});
  std::string commands;
  int tag = 1;
  for (const LabelCluster& c : cluster_labels(points, axes))
    commands += fmt::format("set label {} {} at first {}, first {} offset char 0.8,0.6 font ',9' noenhanced\n", tag++,
                            gp_quote(c.text), c.x, c.y);
  return commands;
}

void chart(const std::string& dir, const SpeedAccuracyRun& run, bool coverage) {
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b",
                                         "#e377c2", "#17becf", "#bcbd22", "#7f7f7f", "#000000"};
  const std::vector<std::string> families = families_of(run);
  std::vector<DataBlock> blocks;
  std::string plot = "plot ";
  for (size_t f = 0; f < families.size(); ++f) {
    DataBlock block{families[f], {{"x", "x", quoted(families[f])}}};
    for (const EntrySummary& e : run.entries)
      if (e.family == families[f])
        block.rows.push_back(
            {fmt::format("{}", e.seconds_per_frame), fmt::format("{}", mismatch_of(e, coverage)), "x"});
    blocks.push_back(block);
    plot += fmt::format("DATA index {} using 1:2 title columnheader(3) with points pt {} ps 1.5 lc rgb '{}', \\\n     ",
                        f, 5 + 2 * int(f % 4), kColours[f % 10]);
  }
  DataBlock front{"Pareto front", {{"x", "x", "\"Pareto front\""}}};
  for (size_t i : pareto_front(run.entries, coverage))
    front.rows.push_back({fmt::format("{}", run.entries[i].seconds_per_frame),
                          fmt::format("{}", mismatch_of(run.entries[i], coverage)), "x"});
  DataBlock reference{"lavapipe", {{"x", "x", "\"lavapipe (Vulkan, the reference)\""}}};
  reference.rows.push_back({fmt::format("{}", run.lavapipe.seconds_per_frame), "0", "x"});
  blocks.push_back(front);
  blocks.push_back(reference);
  plot += fmt::format(
      "DATA index {} using 1:2 title columnheader(3) with linespoints lw 2 pt 6 ps 2.5 lc rgb '#888888', \\\n     "
      "DATA index {} using 1:2 title columnheader(3) with points pt 3 ps 3 lw 2 lc rgb '#d62728'\n",
      families.size(), families.size() + 1);
  const ChartAxes axes = axes_for(run, coverage);
  const std::string measure = coverage ? "coverage (owner)" : "raw depth";
  const std::string body =
      "set key noenhanced outside right top vertical\nset title " +
      gp_quote("Speed against accuracy: " + measure + " mismatch against lavapipe (numbers: the table on the page)") +
      " noenhanced\nset logscale x 10\nset xlabel 'time per frame of the scene set (seconds, log)'\n"
      "set ylabel " +
      gp_quote("samples whose " + measure + " differs from lavapipe (%)") + "\n" +
      fmt::format("set xrange [{}:{}]\nset yrange [{}:{}]\nset ytics 0, {}\nset grid\n", axes.x_min, axes.x_max,
                  axes.y_min, axes.y_max, tick_step(axes.y_max / 1.15)) +
      label_commands(run, coverage, axes) + plot;
  render_chart(dir, coverage ? "speed_accuracy_coverage" : "speed_accuracy_depth", blocks, body);
}

// The page's table: each method's number on the charts, its time and both mismatches.
std::vector<std::vector<std::string>> method_table(const SpeedAccuracyRun& run) {
  std::vector<std::vector<std::string>> table{
      {"#", "family", "method", "ms per frame", "coverage mismatch %", "depth mismatch %"}};
  const auto row = [](const std::string& number, const EntrySummary& e) {
    return std::vector<std::string>{number,
                                    e.family,
                                    e.method,
                                    fmt::format("{:.3f}", e.seconds_per_frame * 1e3),
                                    fmt::format("{:.4f}", e.coverage_mismatch_pct),
                                    fmt::format("{:.4f}", e.depth_mismatch_pct)};
  };
  for (size_t i = 0; i < run.entries.size(); ++i) table.push_back(row(std::to_string(i + 1), run.entries[i]));
  table.push_back(row("ref", run.lavapipe));
  return table;
}

}  // namespace

namespace {

std::string summary_json(const SpeedAccuracyRun& run) {
  nlohmann::ordered_json out;
  const auto entry = [](const EntrySummary& e) {
    return nlohmann::ordered_json{{"family", e.family},
                                  {"method", e.method},
                                  {"seconds_per_frame", e.seconds_per_frame},
                                  {"coverage_mismatch_pct", e.coverage_mismatch_pct},
                                  {"depth_mismatch_pct", e.depth_mismatch_pct}};
  };
  out["lavapipe"] = entry(run.lavapipe);
  out["methods"] = nlohmann::ordered_json::array();
  for (const EntrySummary& e : run.entries) out["methods"].push_back(entry(e));
  for (bool coverage : {true, false}) {
    nlohmann::ordered_json front = nlohmann::ordered_json::array();
    for (size_t i : pareto_front(run.entries, coverage))
      front.push_back(run.entries[i].family + ": " + run.entries[i].method);
    out[coverage ? "pareto_front_coverage" : "pareto_front_depth"] = front;
  }
  return out.dump(2) + "\n";
}

}  // namespace

void write_speed_accuracy_outputs(const std::string& dir, const SpeedAccuracyRun& run) {
  write_json_file(dir, "speed_accuracy.json", summary_json(run));
  chart(dir, run, true);
  chart(dir, run, false);
  write_index_html(
      dir, "Speed against accuracy",
      {{"Coverage",
        "Each CPU method over the scene set (coplanar pair, house, sliver pair, mesh): median time "
        "per frame against the share of samples whose owner differs from lavapipe. Grey: the Pareto "
        "front. Red: lavapipe's own time (GPU submit to fence). Each label lists the numbers of the methods "
        "at that spot; the table below gives each number's method, time and mismatches.",
        {"speed_accuracy_coverage"},
        method_table(run)},
       {"Depth", "The same runs, judged on the raw stored depth.", {"speed_accuracy_depth"}}},
      {kSpeedAccuracyCsv, "speed_accuracy.json"});
}

}  // namespace rastercmp::experiments
