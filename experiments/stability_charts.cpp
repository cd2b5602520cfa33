// stability.json, charts and page of `sweep stability`, from stability.csv read back.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "experiments/doc_table_renderers.hpp"
#include "experiments/failure_boundary.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/map_theory.hpp"
#include "experiments/method_maps.hpp"
#include "experiments/html_page.hpp"
#include "experiments/stability.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {
namespace {

std::string onset_number(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : "NaN"; }

// One panel per mapping (2 x 2); each row's legend once, outside the plots at the outer right.
std::string onset_panel_layout(const std::string& title) {
  return "set multiplot layout 2,2 margins 0.07,0.79,0.08,0.9 spacing 0.09,0.13 title " + gp_quote(title) + "\n";
}

std::string onset_panel_key(DepthMapping mapping) {
  switch (mapping) {
    case DepthMapping::StandardDouble: return "set key at screen 0.995, screen 0.9 right top font ',8' spacing 0.9\n";
    case DepthMapping::ReversedDouble: return "set key at screen 0.995, screen 0.44 right top font ',8' spacing 0.9\n";
    default: return "unset key\n";
  }
}

// fight_vs_far_near: per mapping, per (format, separation), the mean wrong fraction over the jitter
// ensemble against far/near, with bars from the ensemble's smallest to its largest fraction.
void chart_fight_vs_far_near(const std::string& dir, const CsvTable& table) {
  std::vector<DataBlock> blocks;
  const size_t cpu = table.column("value_cpu"), vk = table.column("value_vk");
  const Where base{{"experiment", "fight_onset"}};
  std::string body = onset_panel_layout(
      "Near-coplanar pair (50 units away, 30 degrees): wrong surface against far/near, mean over the jitter "
      "ensemble, bars: least to most");
  body += "set logscale x 10\nset format x '10^{%L}'\nset xlabel 'far / near'\nset yrange [-0.02:1.02]\n"
          "set ylabel 'fraction won by the farther surface'\nset grid\n";
  for (DepthMapping mapping : kDepthMappings) {
    std::string plot;
    size_t style = 0;
    for (const std::string& c : distinct(table, "case", base)) {
      if (case_depth_mapping(c) != mapping) continue;
      for (const std::string& sep : distinct(table, "param_a", {{"experiment", "fight_onset"}, {"case", c}})) {
        ++style;
        DataBlock block{case_depth_format(c) + ", sep " + sep, {}};
        for (const std::string& r : distinct(table, "param_b", {{"experiment", "fight_onset"}, {"case", c}, {"param_a", sep}})) {
          double sum = 0, low = INFINITY, high = -INFINITY;
          size_t n = 0;
          for (const Row& row : select_rows(table, {{"experiment", "fight_onset"}, {"case", c}, {"param_a", sep}, {"param_b", r}})) {
            const double v = std::max(to_double(row[cpu]), to_double(row[vk]));
            sum += v, low = std::min(low, v), high = std::max(high, v), ++n;
          }
          block.rows.push_back({r, onset_number(sum / double(n)), onset_number(low), onset_number(high)});
        }
        plot += fmt::format("DATA index {} using 1:2:3:4 title {} with yerrorlines lt {}, ", blocks.size(),
                            gp_quote(block.title), style);
        blocks.push_back(block);
      }
    }
    if (plot.empty()) continue;
    plot.resize(plot.size() - 2);
    body += "set title " + gp_quote(mapping_name(mapping)) + "\n" + onset_panel_key(mapping) + "plot " + plot + "\n";
  }
  body += "unset multiplot\n";
  render_chart(dir, "fight_vs_far_near", blocks, body);
}

// fight_onset_map: per mapping, the onset over the ensemble against separation per format: median,
// bars from the smallest to the largest onset (an ensemble member that never fights puts its bar at
// the top of the panel), and the predicted onset (predicted_onset) as a dotted line.
void chart_fight_onset_map(const std::string& dir, const CsvTable& table) {
  std::vector<DataBlock> blocks;
  const Where base{{"experiment", "fight_onset"}};
  double top = 1;
  for (const std::string& r : distinct(table, "param_b", base)) top = std::max(top, to_double(r));
  std::string body = onset_panel_layout(
      "Far/near at which the pair starts to fight over the jitter ensemble: median, bars: least to most; dotted: "
      "predicted");
  body += fmt::format(
      "set logscale xy 10\nset format y '10^{{%L}}'\nset format x '%g'\nset yrange [3:{:g}]\nset xrange [0.005:2]\n"
      "set xlabel 'separation between the surfaces (world units)'\nset ylabel 'far/near of the first wrong pixel'\n"
      "set grid\n",
      top * 4);
  for (DepthMapping mapping : kDepthMappings) {
    std::string plot;
    size_t style = 0;
    for (const std::string& c : distinct(table, "case", base)) {
      if (case_depth_mapping(c) != mapping) continue;
      ++style;
      DataBlock block{case_depth_format(c), {}}, theory{case_depth_format(c) + " predicted", {}};
      for (const std::string& sep : distinct(table, "param_a", {{"experiment", "fight_onset"}, {"case", c}})) {
        const OnsetDistribution d = fight_onset_distribution(table, c, sep);
        const auto clip_top = [&](double v) { return std::isfinite(v) ? v : top * 3; };
        block.rows.push_back({sep, onset_number(d.median), onset_number(clip_top(d.min)), onset_number(clip_top(d.max))});
        if (const auto p = predicted_onset(c, to_double(sep))) theory.rows.push_back({sep, onset_number(p->value)});
      }
      plot += fmt::format("DATA index {} using 1:2:3:4 title {} with yerrorlines lt {} ps 1.5, ", blocks.size(),
                          gp_quote(block.title + " (median)"), style);
      blocks.push_back(block);
      if (!theory.rows.empty()) {
        if (theory.rows.size() == 1) {  // one separation (--quick): a short horizontal mark
          theory.rows.push_back({fmt::format("{:g}", to_double(theory.rows[0][0]) * 1.6), theory.rows[0][1]});
          theory.rows[0][0] = fmt::format("{:g}", to_double(theory.rows[0][0]) / 1.6);
        }
        plot += fmt::format("DATA index {} using 1:2 title {} with lines lt {} dt 3 lw 2, ", blocks.size(),
                            gp_quote(theory.title), style);
        blocks.push_back(theory);
      }
    }
    if (plot.empty()) continue;
    plot.resize(plot.size() - 2);
    body += "set title " + gp_quote(mapping_name(mapping)) + "\n" + onset_panel_key(mapping) + "plot " + plot + "\n";
  }
  body += "unset multiplot\n";
  render_chart(dir, "fight_onset_map", blocks, body);
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
      "set multiplot layout {},2 margins 0.08,0.84,0.07,0.9 spacing 0.09,0.09 title 'Sliver pairs: pixels that "
      "differ from lavapipe (number in each cell; one colour scale for every panel)'\n",
      rows);
  for (size_t i = 0; i < blocks.size(); ++i) {
    // The x label only under the bottom row, so each panel title has the room above its panel.
    body += i + 2 < blocks.size() ? "set xlabel ''\n" : "set xlabel 'apex angle (degrees)'\n";
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

// A measured or predicted number, null where there is none (NaN).
nlohmann::ordered_json json_number(double v) { return std::isnan(v) ? nlohmann::ordered_json() : nlohmann::ordered_json(v); }

nlohmann::ordered_json onset_json_number(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json();
}

// One (case, separation) of fight_onset: the onset distribution over the ensemble (null: never
// within the range), beside the predicted onset and whether it lies in (before_min, max].
nlohmann::ordered_json onset_json(const CsvTable& table, const std::string& c, const std::string& sep) {
  const OnsetDistribution d = fight_onset_distribution(table, c, sep);
  nlohmann::ordered_json onsets = nlohmann::ordered_json::array();
  for (double v : d.onsets) onsets.push_back(onset_json_number(v));
  nlohmann::ordered_json out{{"case", c},
                             {"format", case_depth_format(c)},
                             {"mapping", mapping_name(case_depth_mapping(c))},
                             {"separation", to_double(sep)},
                             {"jitters", d.onsets.size()},
                             {"onset_min", onset_json_number(d.min)},
                             {"onset_q1", onset_json_number(d.q1)},
                             {"onset_median", onset_json_number(d.median)},
                             {"onset_q3", onset_json_number(d.q3)},
                             {"onset_max", onset_json_number(d.max)},
                             {"never", d.never},
                             {"onsets", onsets},
                             {"measured_low", onset_json_number(d.before_min)},
                             {"measured_high", onset_json_number(d.max)}};
  if (const auto p = predicted_onset(c, to_double(sep))) {
    out["predicted"] = p->value;
    out["predicted_formula"] = p->formula;
    out["predicted_in_bracket"] = d.never == 0 && std::isfinite(d.max) &&
                                  (std::isnan(d.before_min) || p->value > d.before_min) && p->value <= d.max;
  } else {
    out["predicted"] = nullptr;
    out["predicted_formula"] = "no onset up to far/near 10^6";
    out["predicted_in_bracket"] = d.never == d.onsets.size();
  }
  return out;
}

nlohmann::ordered_json summary(const CsvTable& table) {
  nlohmann::ordered_json out;
  out["fight_onset"] = nlohmann::ordered_json::array();
  for (const std::string& c : distinct(table, "case", {{"experiment", "fight_onset"}}))
    for (const std::string& sep : distinct(table, "param_a", {{"experiment", "fight_onset"}, {"case", c}}))
      out["fight_onset"].push_back(onset_json(table, c, sep));
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
  for (const FailureBoundary& b : failure_boundaries(table)) {
    nlohmann::ordered_json entry = boundary_json(b);
    if (const auto expected = method_map_expectation(b.experiment, b.case_name, b.method)) {
      entry["expected"] = expected->expected;
      if (!std::isnan(expected->marked)) {
        entry["marked"] = expected->marked;
        entry["marked_label"] = expected->marked_label;
      }
      nlohmann::ordered_json points = nlohmann::ordered_json::array();
      size_t agreeing = 0;
      for (const PointCheck& c : check_expectation(table, b, *expected)) {
        agreeing += c.agrees;
        points.push_back({{"param", c.param},
                          {"predicted", to_string(c.predicted.outcome)},
                          {"predicted_coverage_mismatch", json_number(c.predicted.coverage_mismatch)},
                          {"measured", to_string(c.measured)},
                          {"measured_coverage_mismatch", json_number(c.measured_coverage_mismatch)},
                          {"agrees", c.agrees}});
      }
      entry["expected_points_agreeing"] = agreeing;
      entry["expected_holds"] = agreeing == points.size() && !points.empty();
      entry["expected_points"] = points;
    }
    out["boundaries"].push_back(entry);
  }
  return out;
}

}  // namespace

double fight_onset_ratio(const CsvTable& table, const std::string& case_name, const std::string& separation,
                         const std::string& jitter) {
  const size_t ratio = table.column("param_b"), cpu = table.column("value_cpu"), vk = table.column("value_vk");
  double onset = NAN;
  for (const Row& row : select_rows(
           table, {{"experiment", "fight_onset"}, {"case", case_name}, {"param_a", separation}, {"jitter", jitter}}))
    if ((to_double(row[cpu]) > 0 || to_double(row[vk]) > 0) && !(to_double(row[ratio]) >= onset))
      onset = to_double(row[ratio]);
  return onset;
}

OnsetDistribution fight_onset_distribution(const CsvTable& table, const std::string& case_name,
                                           const std::string& separation) {
  OnsetDistribution d;
  const Where where{{"experiment", "fight_onset"}, {"case", case_name}, {"param_a", separation}};
  for (const std::string& j : distinct(table, "jitter", where)) {
    const double onset = fight_onset_ratio(table, case_name, separation, j);
    d.onsets.push_back(std::isnan(onset) ? INFINITY : onset);
    d.never += std::isnan(onset) ? 1 : 0;
  }
  if (d.onsets.empty()) return d;
  std::sort(d.onsets.begin(), d.onsets.end());
  const size_t last = d.onsets.size() - 1;
  double* stats[] = {&d.min, &d.q1, &d.median, &d.q3, &d.max};
  for (size_t k = 0; k < 5; ++k) *stats[k] = d.onsets[(k * last + 2) / 4];
  std::vector<double> grid;
  for (const std::string& r : distinct(table, "param_b", where)) grid.push_back(to_double(r));
  std::sort(grid.begin(), grid.end());
  for (double r : grid)
    if (r < d.min) d.before_min = r;
  return d;
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
  nlohmann::ordered_json out{{"experiment", b.experiment},
                             {"family", b.family},
                             {"case", b.case_name},
                             {"method", b.method},
                             {"last_clean", json_number(b.last_clean)},
                             {"boundary", json_number(b.boundary)},
                             {"points", b.points},
                             {"failing", b.failing},
                             {"refused", b.refused},
                             {"refused_values", b.refused_values}};
  if (const auto prediction = predicted_boundary(b.experiment, b.case_name, b.method)) {
    const BracketCheck bracket = check_bracket(b, prediction->value, prediction->clean_at_value);
    out["predicted"] = prediction->value;
    out["predicted_formula"] = prediction->formula;
    out["measured_low"] = json_number(bracket.measured_low);
    out["measured_high"] = json_number(bracket.measured_high);
    out["predicted_in_bracket"] = bracket.in_bracket;
  }
  return out;
}

void write_stability_outputs(const std::string& dir) {
  const CsvTable table = read_csv((std::filesystem::path(dir) / kStabilityCsv).string());
  const std::string json = summary(table).dump(2) + "\n";
  write_json_file(dir, "stability.json", json);
  write_stability_tables(dir, json);
  chart_fight_vs_far_near(dir, table);
  chart_fight_onset_map(dir, table);
  chart_slivers(dir, table);
  std::vector<PageSection> sections{
      {"Z-fighting onset",
        "A near-coplanar pair 50 units away at 30 degrees, in each depth format and with each clip-z mapping "
        "(standard or reversed, clip z formed in float as a camera matrix does or in double from w), rendered at an "
        "ensemble of jitters (sub-pixel offset and depth phase); the onset is the first far/near ratio at which the "
        "farther surface wins a pixel, one per jitter (stability.json: min, quartiles, max, and the predicted onset).",
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
