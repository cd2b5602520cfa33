// stability.json, charts and page of `sweep stability`, from stability.csv read back.
#include <algorithm>
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

// One panel per fill method, on one colour scale (one colour bar, right of the panels), each cell
// also labelled with its count; both axes logarithmic over the grid's own range.
void chart_slivers(const std::string& dir, const CsvTable& table) {
  std::vector<DataBlock> blocks;
  const size_t a = table.column("param_a"), b = table.column("param_b"), miss = table.column("coverage_mismatch");
  const std::vector<std::string> methods = distinct(table, "method", {{"experiment", "sliver"}});
  double highest = 0, a_low = INFINITY, a_high = 0, b_low = INFINITY, b_high = 0;
  for (const std::string& method : methods) {
    DataBlock block{method, {}};
    for (const Row& row : select_rows(table, {{"experiment", "sliver"}, {"method", method}})) {
      const double angle = to_double(row[a]), length = to_double(row[b]), count = to_double(row[miss]);
      a_low = std::min(a_low, angle), a_high = std::max(a_high, angle);
      b_low = std::min(b_low, length), b_high = std::max(b_high, length);
      if (!std::isnan(count)) highest = std::max(highest, count);
      block.rows.push_back({row[a], row[b], std::isnan(count) ? "NaN" : row[miss],
                            std::isnan(count) ? "\"refused\"" : row[miss]});
    }
    blocks.push_back(block);
  }
  if (blocks.empty()) return;
  const size_t rows = (blocks.size() + 1) / 2;
  std::string body = fmt::format(
      "set logscale xy 10\nset xrange [{:g}:{:g}]\nset yrange [{:g}:{:g}]\nset xlabel 'apex angle (degrees)'\n"
      "set ylabel 'edge length (px)'\nset palette defined (0 '#f7f7f7', 1 '#fdae61', 2 '#d7191c')\n"
      "set cbrange [0:{:g}]\nunset colorbox\nset grid\n",
      a_low / 2, a_high * 2, b_low / 1.6, b_high * 1.6, std::max(highest, 1.0));
  body += fmt::format(
      "set multiplot layout {},2 margins 0.08,0.86,0.07,0.9 spacing 0.09,0.11 title 'Sliver pairs: pixels that "
      "differ from lavapipe (number in each cell; one colour scale for every panel)'\n",
      rows);
  for (size_t i = 0; i < blocks.size(); ++i) {
    if (i + 1 == blocks.size())
      body += "set colorbox user origin screen 0.9, screen 0.2 size screen 0.025, screen 0.6\n"
              "set cblabel 'pixels that differ from lavapipe'\n";
    body += fmt::format(
        "set title {} noenhanced\nplot DATA index {} using 1:2:3 with points pt 5 ps 4 palette notitle, "
        "'' index {} using 1:2:4 with labels font ',9' notitle\n",
        gp_quote(methods[i]), i, i);
  }
  body += "unset multiplot\n";
  render_chart(dir, "sliver_map", blocks, body);
}

// A limit chart (far_distance, near_w) against its parameter on a symmetric log axis, or, when every
// point matches lavapipe, the table of its points instead (limit_blocks, limit_zero_table).
PageSection chart_limit(const std::string& dir, const CsvTable& table, const std::string& experiment,
                        const std::string& heading, const std::string& title, const std::string& xlabel) {
  const std::vector<DataBlock> blocks = limit_blocks(table, experiment);
  PageSection section{heading, title + ".", {}};
  if (only_zeros(blocks, 2)) {
    section.text += " Every point matches lavapipe (coverage and depth mismatch 0), so there is no chart; the points:";
    section.table = limit_zero_table(table, experiment);
    return section;
  }
  std::vector<double> values;
  std::vector<std::string> labels;
  for (const std::string& p : distinct(table, "param_a", {{"experiment", experiment}})) {
    values.push_back(to_double(p));
    labels.push_back(p);
  }
  const SymlogAxis axis(values);
  std::string body = "set title " + gp_quote(title) + "\nset xlabel " +
                     gp_quote(xlabel + " (symmetric log scale, 0 at its tic)") +
                     "\nset ylabel 'samples that differ from lavapipe'\nset yrange [-0.5:*]\nset key below\nset grid\n";
  body += experiment == "non_finite" ? "set xtics rotate by -45 (" : axis.tics_command("x", labels);
  if (experiment == "non_finite") {
    for (size_t i = 0; i < blocks.front().rows.size(); ++i)
      body += (i ? ", " : "") + gp_quote(blocks.front().rows[i][1]) + " " + blocks.front().rows[i][0];
    body += ")\n";
  }
  body += "plot for [i=0:1] DATA index i using 1:3 title columnheader(1) with linespoints lt (i+1)\n";
  std::vector<DataBlock> headed = blocks;
  for (DataBlock& block : headed) block.rows.insert(block.rows.begin(), {block.title, "x", "x"});
  render_chart(dir, experiment, headed, body);
  section.charts.push_back(experiment);
  return section;
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
  out["boundaries"] = nlohmann::ordered_json::array();
  for (const FailureBoundary& b : failure_boundaries(table)) out["boundaries"].push_back(boundary_json(b));
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

std::vector<DataBlock> limit_blocks(const CsvTable& table, const std::string& experiment) {
  const size_t c = table.column("case"), a = table.column("param_a"), cov = table.column("coverage_mismatch"),
               dep = table.column("depth_mismatch");
  const std::vector<Row> rows = select_rows(table, {{"experiment", experiment}});
  std::vector<double> parameters;
  for (const Row& row : rows) parameters.push_back(to_double(row[a]));
  const SymlogAxis axis(parameters);
  DataBlock coverage{"coverage", {}}, depth{"depth", {}};
  size_t i = 0;
  for (const Row& row : rows) {
    // NaN / infinite parameters (non_finite) are categories in row order; numbers sit on the axis.
    const double p = to_double(row[a]);
    const bool category = experiment == "non_finite" || !std::isfinite(p);
    const std::string x = category ? std::to_string(i) : fmt::format("{:.10g}", axis.position(p));
    const std::string label = category ? row[c] + "=" + row[a] : row[a];
    coverage.rows.push_back({x, label, row[cov]});
    depth.rows.push_back({x, label, row[dep]});
    ++i;
  }
  return {coverage, depth};
}

std::vector<std::vector<std::string>> limit_zero_table(const CsvTable& table, const std::string& experiment) {
  const size_t c = table.column("case"), m = table.column("method"), a = table.column("param_a"),
               cov = table.column("coverage_mismatch"), dep = table.column("depth_mismatch"),
               agree = table.column("cpu_vk_agree");
  std::vector<std::vector<std::string>> out{
      {"case", "method", "parameter", "coverage mismatch", "depth mismatch", "identical to lavapipe"}};
  for (const Row& row : select_rows(table, {{"experiment", experiment}}))
    out.push_back({row[c], row[m], row[a], row[cov], row[dep], row[agree]});
  return out;
}

nlohmann::ordered_json boundary_json(const FailureBoundary& b) {
  const auto number = [](double v) { return std::isnan(v) ? nlohmann::ordered_json() : nlohmann::ordered_json(v); };
  nlohmann::ordered_json out{{"experiment", b.experiment},
                             {"family", b.family},
                             {"case", b.case_name},
                             {"method", b.method},
                             {"last_clean", number(b.last_clean)},
                             {"boundary", number(b.boundary)},
                             {"points", b.points},
                             {"failing", b.failing},
                             {"refused", b.refused},
                             {"refused_values", b.refused_values}};
  if (const auto prediction = predicted_boundary(b.experiment, b.case_name, b.method)) {
    const BracketCheck bracket = check_bracket(b, prediction->value);
    out["predicted"] = prediction->value;
    out["predicted_formula"] = prediction->formula;
    out["measured_low"] = number(bracket.measured_low);
    out["measured_high"] = number(bracket.measured_high);
    out["predicted_in_bracket"] = bracket.in_bracket;
  }
  return out;
}

void write_stability_outputs(const std::string& dir) {
  const CsvTable table = read_csv((std::filesystem::path(dir) / kStabilityCsv).string());
  write_json_file(dir, "stability.json", summary(table).dump(2) + "\n");
  chart_fight_onset(dir, table);
  chart_slivers(dir, table);
  std::vector<PageSection> sections{
      {"Z-fighting onset",
        "A near-coplanar pair; the first far/near ratio at which the farther surface wins a pixel.",
        {"fight_vs_far_near", "fight_onset_map"}},
      {"Slivers",
       "Two thin triangles sharing an edge through a pixel centre, every fill method; colour and number: pixels "
       "that differ from lavapipe, on one scale for every panel.",
       {"sliver_map"}}};
  sections.push_back(chart_limit(dir, table, "far_distance", "Limits of the exact path: far from the origin",
                                 "Exact path: a thin triangle reaching far from the origin",
                                 "window x of the far vertex (pixels; viewportBoundsRange ends at 32768)"));
  sections.push_back(chart_limit(dir, table, "near_w", "Limits of the exact path: w near 0",
                                 "Exact path: a vertex on the near plane with w approaching 0", "clip w of the vertex"));
  sections.push_back(chart_limit(dir, table, "non_finite", "Limits of the exact path: NaN and infinite inputs",
                                 "Exact path: NaN and infinite vertex components", "component = value"));
  for (PageSection& section : write_method_map_charts(dir, table)) sections.push_back(std::move(section));
  write_index_html(dir, "Stability: where methods fail", sections, {kStabilityCsv, "stability.json"});
}

}  // namespace rastercmp::experiments
