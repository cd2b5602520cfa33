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

// speed_accuracy_coverage / _depth for the triangle set, speed_accuracy_lines_coverage / _depth for lines.
std::string chart_name(const SceneSetRun& run, bool coverage) {
  return std::string("speed_accuracy_") + (run.name == "lines" ? "lines_" : "") + (coverage ? "coverage" : "depth");
}

double mismatch_of(const EntrySummary& e, bool coverage) {
  return coverage ? e.coverage_mismatch_pct : e.depth_mismatch_pct;
}

// Families in order of first appearance: one series (colour, point type) each.
std::vector<std::string> families_of(const SceneSetRun& run) {
  std::vector<std::string> families;
  for (const EntrySummary& e : run.entries)
    if (std::find(families.begin(), families.end(), e.family) == families.end()) families.push_back(e.family);
  return families;
}

// Axes fixed by the data: x (log) spans every time including lavapipe's with a margin; y starts a
// little below 0 so that points at 0 stand clear of the axis, with ticks from 0.
ChartAxes axes_for(const SceneSetRun& run, bool coverage) {
  double x_min = run.lavapipe.seconds_low, x_max = run.lavapipe.seconds_high, y_max = 0;
  for (const EntrySummary& e : run.entries) {
    x_min = std::min(x_min, e.seconds_low);
    x_max = std::max(x_max, e.seconds_high);
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

std::string label_commands(const SceneSetRun& run, bool coverage, const ChartAxes& axes) {
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

void chart(const std::string& dir, const SceneSetRun& run, bool coverage) {
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b",
                                         "#e377c2", "#17becf", "#bcbd22", "#7f7f7f", "#000000"};
  const std::vector<std::string> families = families_of(run);
  std::vector<DataBlock> blocks;
  std::string plot = "plot ";
  for (size_t f = 0; f < families.size(); ++f) {
    DataBlock block{families[f], {{"x", "x", quoted(families[f]), "x", "x"}}};
    for (const EntrySummary& e : run.entries)
      if (e.family == families[f])
        block.rows.push_back({fmt::format("{}", e.seconds_per_frame), fmt::format("{}", mismatch_of(e, coverage)), "x",
                              fmt::format("{}", e.seconds_low), fmt::format("{}", e.seconds_high)});
    blocks.push_back(block);
    // The median with its 95% interval as a horizontal error bar.
    plot += fmt::format(
        "DATA index {} using 1:2:4:5 title columnheader(3) with xerrorbars pt {} ps 1.5 lc rgb '{}', \\\n     ", f,
        5 + 2 * int(f % 4), kColours[f % 10]);
  }
  DataBlock front{"Pareto front", {{"x", "x", "\"Pareto front\""}}};
  for (size_t i : pareto_front(run.entries, coverage))
    front.rows.push_back({fmt::format("{}", run.entries[i].seconds_per_frame),
                          fmt::format("{}", mismatch_of(run.entries[i], coverage)), "x"});
  DataBlock reference{"lavapipe", {{"x", "x", "\"lavapipe (Vulkan, the reference)\"", "x", "x"}}};
  reference.rows.push_back({fmt::format("{}", run.lavapipe.seconds_per_frame), "0", "x",
                            fmt::format("{}", run.lavapipe.seconds_low), fmt::format("{}", run.lavapipe.seconds_high)});
  blocks.push_back(front);
  blocks.push_back(reference);
  plot += fmt::format(
      "DATA index {} using 1:2 title columnheader(3) with linespoints lw 2 pt 6 ps 2.5 lc rgb '#888888', \\\n     "
      "DATA index {} using 1:2:4:5 title columnheader(3) with xerrorbars pt 3 ps 3 lw 2 lc rgb '#d62728'\n",
      families.size(), families.size() + 1);
  const ChartAxes axes = axes_for(run, coverage);
  const std::string measure = coverage ? "coverage (owner)" : "raw depth";
  const std::string body =
      "set key noenhanced outside right top vertical\nset title " +
      gp_quote("Speed against accuracy, " + run.name + ": " + measure + " mismatch (numbers: the page's table)") +
      " noenhanced\nset logscale x 10\nset xlabel 'time per frame of the scene set (seconds, log; bars: 95% interval of the median)'\n"
      "set ylabel " +
      gp_quote("samples whose " + measure + " differs from lavapipe (%)") + "\n" +
      fmt::format("set xrange [{}:{}]\nset yrange [{}:{}]\nset ytics 0, {}\nset grid\n", axes.x_min, axes.x_max,
                  axes.y_min, axes.y_max, tick_step(axes.y_max / 1.15)) +
      label_commands(run, coverage, axes) + plot;
  render_chart(dir, chart_name(run, coverage), blocks, body);
}

// The page's table: each method's number on the charts, its time and both mismatches.
std::vector<std::vector<std::string>> method_table(const SceneSetRun& run) {
  std::vector<std::vector<std::string>> table{
      {"#", "family", "method", "ms per frame (median)", "interval (ms)", "coverage mismatch %", "depth mismatch %"}};
  const auto row = [](const std::string& number, const EntrySummary& e) {
    return std::vector<std::string>{number,
                                    e.family,
                                    e.method,
                                    fmt::format("{:.3f}", e.seconds_per_frame * 1e3),
                                    fmt::format("{:.3f} .. {:.3f}", e.seconds_low * 1e3, e.seconds_high * 1e3),
                                    fmt::format("{:.4f}", e.coverage_mismatch_pct),
                                    fmt::format("{:.4f}", e.depth_mismatch_pct)};
  };
  for (size_t i = 0; i < run.entries.size(); ++i) table.push_back(row(std::to_string(i + 1), run.entries[i]));
  table.push_back(row("ref", run.lavapipe));
  return table;
}

}  // namespace

namespace {

// Each family's Pareto front (with the exact and fast paths), as a page table.
std::vector<std::vector<std::string>> fronts_table(const SceneSetRun& run) {
  std::vector<std::vector<std::string>> table{{"family", "measure", "Pareto front (fastest first; # as in the table above)"}};
  for (bool coverage : {true, false})
    for (const auto& [family, front] : family_pareto_fronts(run.entries, coverage)) {
      std::string text;
      for (size_t i : front) text += (text.empty() ? "" : ", ") + run.entries[i].method + " (#" + std::to_string(i + 1) + ")";
      table.push_back({family, coverage ? "coverage" : "depth", text});
    }
  return table;
}

nlohmann::ordered_json entry_json(const EntrySummary& e) {
  return nlohmann::ordered_json{{"family", e.family},
                                {"method", e.method},
                                {"seconds_per_frame", e.seconds_per_frame},
                                {"seconds_ci_low", e.seconds_low},
                                {"seconds_ci_high", e.seconds_high},
                                {"ci_coverage", e.ci_coverage},
                                {"coverage_mismatch_pct", e.coverage_mismatch_pct},
                                {"depth_mismatch_pct", e.depth_mismatch_pct}};
}

std::string summary_json(const SpeedAccuracyRun& run) {
  nlohmann::ordered_json out;
  out["repeats"] = run.repeats;
  out["sets"] = nlohmann::ordered_json::array();
  for (const SceneSetRun& set : run.sets) {
    nlohmann::ordered_json s;
    s["scene_set"] = set.name;
    s["lavapipe"] = entry_json(set.lavapipe);
    s["methods"] = nlohmann::ordered_json::array();
    for (const EntrySummary& e : set.entries) s["methods"].push_back(entry_json(e));
    for (bool coverage : {true, false}) {
      nlohmann::ordered_json front = nlohmann::ordered_json::array();
      for (size_t i : pareto_front(set.entries, coverage))
        front.push_back(set.entries[i].family + ": " + set.entries[i].method);
      s[coverage ? "pareto_front_coverage" : "pareto_front_depth"] = front;
      nlohmann::ordered_json families;
      for (const auto& [family, indices] : family_pareto_fronts(set.entries, coverage)) {
        families[family] = nlohmann::ordered_json::array();
        for (size_t i : indices) families[family].push_back(set.entries[i].family + ": " + set.entries[i].method);
      }
      s[coverage ? "family_fronts_coverage" : "family_fronts_depth"] = families;
    }
    out["sets"].push_back(s);
  }
  return out.dump(2) + "\n";
}

}  // namespace

void write_speed_accuracy_outputs(const std::string& dir, const SpeedAccuracyRun& run) {
  write_json_file(dir, "speed_accuracy.json", summary_json(run));
  std::vector<PageSection> sections;
  for (const SceneSetRun& set : run.sets) {
    chart(dir, set, true);
    chart(dir, set, false);
    const std::string scenes = set.name == "lines" ? "64 one-pixel lines radiating in a 256x256 frame"
                                                   : "coplanar pair, house, sliver pair, mesh";
    sections.push_back(
        {"Coverage, " + set.name,
         "Each CPU method over the scene set (" + scenes + "): the median time per frame over " +
             std::to_string(run.repeats) +
             " interleaved repetitions, with the order-statistics 95% interval of the median as an error bar, against "
             "the share of samples whose owner differs from lavapipe. Grey: the Pareto front over all methods. Red: "
             "lavapipe's own time (GPU submit to fence). Each label lists the numbers of the methods at that spot; "
             "the table gives each number's method, time and mismatches.",
         {chart_name(set, true)},
         method_table(set)});
    sections.push_back({"Depth, " + set.name, "The same runs, judged on the raw stored depth.", {chart_name(set, false)}});
    sections.push_back({"Pareto fronts per family, " + set.name,
                        "For each family: its methods with the exact path and the fast path; a method is on the front "
                        "when no other is both faster (median) and closer to lavapipe.",
                        {},
                        fronts_table(set)});
  }
  write_index_html(dir, "Speed against accuracy", sections, {kSpeedAccuracyCsv, "speed_accuracy.json"});
}

}  // namespace rastercmp::experiments
