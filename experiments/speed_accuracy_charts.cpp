// Charts, JSON and page of `chart speed-accuracy`.
#include <filesystem>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "experiments/gnuplot.hpp"
#include "experiments/html_page.hpp"
#include "experiments/speed_accuracy.hpp"

namespace rastercmp::experiments {
namespace {

std::string quoted(const std::string& text) { return "\"" + text + "\""; }

void chart(const std::string& dir, const SpeedAccuracyRun& run, bool coverage) {
  const auto miss = [&](const EntrySummary& e) { return coverage ? e.coverage_mismatch_pct : e.depth_mismatch_pct; };
  DataBlock points{"methods", {{"x", "x", "methods"}}};
  for (const EntrySummary& e : run.entries)
    points.rows.push_back({fmt::format("{}", e.seconds_per_frame), fmt::format("{}", miss(e)), quoted(e.family + ": " + e.method)});
  DataBlock front{"Pareto front", {{"x", "x", "\"Pareto front\""}}};
  for (size_t i : pareto_front(run.entries, coverage))
    front.rows.push_back({fmt::format("{}", run.entries[i].seconds_per_frame), fmt::format("{}", miss(run.entries[i])), "x"});
  DataBlock reference{"lavapipe", {{"x", "x", "\"lavapipe (Vulkan, the reference)\""}},};
  reference.rows.push_back({fmt::format("{}", run.lavapipe.seconds_per_frame), "0", "lavapipe"});
  const std::string measure = coverage ? "coverage (owner)" : "raw depth";
  const std::string body =
      "set title " + gp_quote("Speed against accuracy: " + measure + " mismatch against lavapipe") +
      "\nset logscale x 10\nset xlabel 'time per frame of the scene set (seconds, log)'\n"
      "set ylabel " + gp_quote("samples whose " + measure + " differs from lavapipe (%)") +
      "\nset yrange [-1:*]\nset offsets graph 0.1, graph 0.3, graph 0.05, 0\nset key outside bottom center horizontal\nset grid\n"
      "plot DATA index 1 using 1:2 title columnheader(3) with linespoints lw 2 pt 6 ps 2.5 lc rgb '#888888', \\\n"
      "     DATA index 0 using 1:2 title 'CPU methods' with points pt 7 ps 1.5 lc rgb '#1f77b4', \\\n"
      "     DATA index 0 using 1:2:3 every ::1 notitle with labels rotate by 50 left offset 0.8,0.3 font ',9', \\\n"
      "     DATA index 2 using 1:2 title columnheader(3) with points pt 3 ps 3 lw 2 lc rgb '#d62728'\n";
  render_chart(dir, coverage ? "speed_accuracy_coverage" : "speed_accuracy_depth", {points, front, reference}, body);
}

std::string summary_json(const SpeedAccuracyRun& run) {
  nlohmann::ordered_json out;
  const auto entry = [](const EntrySummary& e) {
    return nlohmann::ordered_json{{"family", e.family}, {"method", e.method}, {"seconds_per_frame", e.seconds_per_frame},
                                  {"coverage_mismatch_pct", e.coverage_mismatch_pct},
                                  {"depth_mismatch_pct", e.depth_mismatch_pct}};
  };
  out["lavapipe"] = entry(run.lavapipe);
  out["methods"] = nlohmann::ordered_json::array();
  for (const EntrySummary& e : run.entries) out["methods"].push_back(entry(e));
  for (bool coverage : {true, false}) {
    nlohmann::ordered_json front = nlohmann::ordered_json::array();
    for (size_t i : pareto_front(run.entries, coverage)) front.push_back(run.entries[i].family + ": " + run.entries[i].method);
    out[coverage ? "pareto_front_coverage" : "pareto_front_depth"] = front;
  }
  return out.dump(2) + "\n";
}

}  // namespace

void write_speed_accuracy_outputs(const std::string& dir, const SpeedAccuracyRun& run) {
  write_json_file(dir, "speed_accuracy.json", summary_json(run));
  chart(dir, run, true);
  chart(dir, run, false);
  write_index_html(dir, "Speed against accuracy",
                   {{"Coverage", "Each CPU method over the scene set (coplanar pair, house, sliver pair, mesh): median time "
                                 "per frame against the share of samples whose owner differs from lavapipe. Grey: the Pareto "
                                 "front. Red: lavapipe's own time (GPU submit to fence).",
                     {"speed_accuracy_coverage"}},
                    {"Depth", "The same runs, judged on the raw stored depth.", {"speed_accuracy_depth"}}},
                   {kSpeedAccuracyCsv, "speed_accuracy.json"});
}

}  // namespace rastercmp::experiments
