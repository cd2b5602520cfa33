// stability.json, charts and page of `sweep stability`, from stability.csv read back.
#include <cmath>
#include <filesystem>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "experiments/failure_boundary.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/method_maps.hpp"
#include "experiments/html_page.hpp"
#include "experiments/stability.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {
namespace {

std::string plot_blocks(size_t count, const std::string& using_clause, const std::string& style) {
  return "plot for [i=0:" + std::to_string(count - 1) + "] DATA index i using " + using_clause +
         " title columnheader(1) " + style + "\n";
}

void chart_fight_onset(const std::string& dir, const CsvTable& table) {
  std::vector<DataBlock> lines, onsets;
  const size_t ratio = table.column("param_b"), wrong = table.column("value_cpu");
  const Where base{{"experiment", "fight_onset"}};
  for (const std::string& format : distinct(table, "case", base)) {
    DataBlock onset{format, {{format, "x"}}};
    for (const std::string& sep : distinct(table, "param_a", base)) {
      const std::string title = format + ", separation " + sep;
      DataBlock block{title, {{"\"" + title + "\"", "x"}}};
      for (const Row& row : select_rows(table, {{"experiment", "fight_onset"}, {"case", format}, {"param_a", sep}}))
        block.rows.push_back({row[ratio], row[wrong]});
      lines.push_back(block);
      const double r = fight_onset_ratio(table, format, sep);
      onset.rows.push_back({sep, std::isnan(r) ? "NaN" : fmt::format("{}", r)});
    }
    onsets.push_back(onset);
  }
  render_chart(
      dir, "fight_vs_far_near", lines,
      "set title 'Two surfaces a given distance apart (50 units away, 30 degrees): wrong surface against far/near'\n"
      "set logscale x 10\nset format x '10^{%L}'\nset xlabel 'far / near'\nset yrange [-0.02:1.02]\n"
      "set ylabel 'fraction won by the farther surface'\nset key outside right top\nset grid\n" +
          plot_blocks(lines.size(), "1:2", "with linespoints lt (i+1)"));
  render_chart(
      dir, "fight_onset_map", onsets,
      "set title 'Far/near ratio at which surfaces start to fight, per depth format'\n"
      "set logscale xy 10\nset format y '10^{%L}'\nset xlabel 'separation between the surfaces (world units)'\n"
      "set ylabel 'smallest far/near with a wrong pixel'\nset key outside right top\nset grid\n" +
          plot_blocks(onsets.size(), "1:2", "with linespoints lt (i+1)"));
}

void chart_slivers(const std::string& dir, const CsvTable& table) {
  std::vector<DataBlock> blocks;
  const size_t a = table.column("param_a"), b = table.column("param_b"), miss = table.column("coverage_mismatch");
  const std::vector<std::string> methods = distinct(table, "method", {{"experiment", "sliver"}});
  for (const std::string& method : methods) {
    DataBlock block{method, {{"\"" + method + "\"", "x", "x"}}};
    for (const Row& row : select_rows(table, {{"experiment", "sliver"}, {"method", method}}))
      block.rows.push_back({row[a], row[b], row[miss]});
    blocks.push_back(block);
  }
  std::string body =
      "set logscale x 10\nset xlabel 'apex angle (degrees)'\nset ylabel 'edge length (pixels)'\n"
      "set cblabel 'pixels that differ from lavapipe'\nset palette defined (0 '#f0f0f0', 1 '#fdae61', 2 '#d7191c')\n"
      "set cbrange [0:*]\nset offsets graph 0.05, graph 0.05, graph 0.08, graph 0.08\n";
  body += fmt::format("set multiplot layout {},2 title 'Sliver pairs: coverage errors against lavapipe'\n",
                      (blocks.size() + 1) / 2);
  for (size_t i = 0; i < blocks.size(); ++i)
    body += fmt::format(
        "set title {} noenhanced\nplot DATA index {} using 1:2:3 every ::1 with points pt 5 ps 3 palette notitle\n",
        gp_quote(methods[i]), i);
  body += "unset multiplot\n";
  render_chart(dir, "sliver_map", blocks, body);
}

// Mismatches of one experiment against its parameter (log x; a parameter of 0 at a labelled floor).
void chart_limit(const std::string& dir, const CsvTable& table, const std::string& experiment, const std::string& title,
                 const std::string& xlabel) {
  const size_t a = table.column("param_a"), cov = table.column("coverage_mismatch"),
               dep = table.column("depth_mismatch");
  DataBlock coverage{"coverage", {{"coverage", "x"}}}, depth{"depth", {{"depth", "x"}}};
  const std::vector<Row> rows = select_rows(table, {{"experiment", experiment}});
  std::vector<double> parameters;
  for (const Row& row : rows) parameters.push_back(to_double(row[a]));
  const double floor = log_axis_floor(parameters);  // a parameter of 0 is drawn there, tic "0"
  bool has_zero = false;
  for (const Row& row : rows) {
    const double p = to_double(row[a]);
    if (p < 0 || std::isnan(p)) continue;  // no place on a log axis
    has_zero = has_zero || p == 0;
    const std::string x = p == 0 ? fmt::format("{:g}", floor) : row[a];
    coverage.rows.push_back({x, row[cov]});
    depth.rows.push_back({x, row[dep]});
  }
  render_chart(dir, experiment, {coverage, depth},
               "set title " + gp_quote(title) + "\nset logscale x 10\nset format x '10^{%L}'\nset xlabel " +
                   gp_quote(xlabel) +
                   "\nset ylabel 'samples that differ from lavapipe'\nset yrange [-0.5:*]\n"
                   "set key outside right top\nset grid\n" +
                   (has_zero ? zero_tic_command("x", floor) : std::string()) +
                   plot_blocks(2, "1:2", "with linespoints lt (i+1)"));
}

void chart_non_finite(const std::string& dir, const CsvTable& table) {
  const size_t c = table.column("case"), a = table.column("param_a"), cov = table.column("coverage_mismatch"),
               dep = table.column("depth_mismatch");
  DataBlock coverage{"coverage", {{"x", "coverage", "x"}}}, depth{"depth", {{"x", "depth", "x"}}};
  std::string tics;
  size_t i = 0;
  for (const Row& row : select_rows(table, {{"experiment", "non_finite"}})) {
    coverage.rows.push_back({std::to_string(i), row[c] + "=" + row[a], row[cov]});
    depth.rows.push_back({std::to_string(i), row[c] + "=" + row[a], row[dep]});
    tics += (i ? ", " : "") + gp_quote(row[c] + "=" + row[a]) + " " + std::to_string(i);
    ++i;
  }
  render_chart(dir, "non_finite", {coverage, depth},
               "set title 'NaN and infinite vertex components: samples that differ from lavapipe'\n"
               "set xtics (" +
                   tics +
                   ") rotate by -45\nset yrange [-0.5:*]\nset ylabel 'samples'\n"
                   "set key outside right top\nset grid\n"
                   "plot for [i=0:1] DATA index i using 1:3 title columnheader(2) with points pt (i==0?7:2) ps 2\n");
}

nlohmann::ordered_json summary(const CsvTable& table) {
  nlohmann::ordered_json out;
  out["fight_onset"] = nlohmann::ordered_json::array();
  for (const std::string& format : distinct(table, "case", {{"experiment", "fight_onset"}}))
    for (const std::string& sep : distinct(table, "param_a", {{"experiment", "fight_onset"}, {"case", format}})) {
      const double r = fight_onset_ratio(table, format, sep);
      out["fight_onset"].push_back(
          {{"format", format},
           {"separation", to_double(sep)},
           {"onset_far_near", std::isnan(r) ? nlohmann::ordered_json() : nlohmann::ordered_json(r)}});
    }
  const size_t agree = table.column("cpu_vk_agree"), method = table.column("method");
  for (const char* experiment : {"sliver", "far_distance", "near_w", "non_finite"}) {
    nlohmann::ordered_json per_method;
    for (const Row& row : select_rows(table, {{"experiment", experiment}})) {
      auto& entry = per_method[row[method]];
      if (entry.is_null()) entry = {{"points", 0}, {"points_identical_to_lavapipe", 0}};
      entry["points"] = entry["points"].get<int>() + 1;
      if (row[agree] == "true")
        entry["points_identical_to_lavapipe"] = entry["points_identical_to_lavapipe"].get<int>() + 1;
    }
    out[experiment] = per_method;
  }
  const auto number = [](double v) { return std::isnan(v) ? nlohmann::ordered_json() : nlohmann::ordered_json(v); };
  out["boundaries"] = nlohmann::ordered_json::array();
  for (const FailureBoundary& b : failure_boundaries(table))
    out["boundaries"].push_back({{"experiment", b.experiment},
                                 {"family", b.family},
                                 {"case", b.case_name},
                                 {"method", b.method},
                                 {"last_clean", number(b.last_clean)},
                                 {"boundary", number(b.boundary)},
                                 {"points", b.points},
                                 {"failing", b.failing},
                                 {"refused", b.refused}});
  return out;
}

}  // namespace

double fight_onset_ratio(const CsvTable& table, const std::string& format, const std::string& separation) {
  const size_t ratio = table.column("param_b"), cpu = table.column("value_cpu"), vk = table.column("value_vk");
  double onset = NAN;
  for (const Row& row : select_rows(table, {{"experiment", "fight_onset"}, {"case", format}, {"param_a", separation}}))
    if ((to_double(row[cpu]) > 0 || to_double(row[vk]) > 0) && !(to_double(row[ratio]) >= onset))
      onset = to_double(row[ratio]);
  return onset;
}

void write_stability_outputs(const std::string& dir) {
  const CsvTable table = read_csv((std::filesystem::path(dir) / kStabilityCsv).string());
  write_json_file(dir, "stability.json", summary(table).dump(2) + "\n");
  chart_fight_onset(dir, table);
  chart_slivers(dir, table);
  chart_limit(dir, table, "far_distance", "Exact path: a thin triangle reaching far from the origin",
              "window x of the far vertex (pixels; viewportBoundsRange ends at 32768)");
  chart_limit(dir, table, "near_w", "Exact path: a vertex on the near plane with w approaching 0",
              "clip w of the vertex");
  chart_non_finite(dir, table);
  std::vector<PageSection> sections{
      {"Z-fighting onset",
        "A near-coplanar pair; the first far/near ratio at which the farther surface wins a pixel.",
        {"fight_vs_far_near", "fight_onset_map"}},
      {"Slivers",
       "Two thin triangles sharing an edge through a pixel centre, every fill method; colour: pixels that differ "
       "from lavapipe.",
       {"sliver_map"}},
      {"Limits of the exact path",
        "Large window coordinates, w near 0, and NaN / infinite inputs (zero is exact).",
        {"far_distance", "near_w", "non_finite"}}};
  for (PageSection& section : write_method_map_charts(dir, table)) sections.push_back(std::move(section));
  write_index_html(dir, "Stability: where methods fail", sections, {kStabilityCsv, "stability.json"});
}

}  // namespace rastercmp::experiments
