// Charts, JSON and page of `chart speed-accuracy`.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "experiments/doc_table_renderers.hpp"
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

std::string measure_name(bool coverage) { return coverage ? "coverage (owner)" : "raw depth"; }

// The set with every time field on the run's clock: what the fronts and charts rank by.
SceneSetRun ranked(const SceneSetRun& set, FrontClock clock) {
  SceneSetRun out = set;
  for (EntrySummary& e : out.entries) e = timed_by(e, clock);
  out.lavapipe = timed_by(set.lavapipe, clock);
  return out;
}

std::string time_name(FrontClock clock) {
  return clock == FrontClock::Cpu ? "CPU time (scalar: thread; fast path, lavapipe: process)" : "wall time";
}

// The set's overview: speed_accuracy_coverage / _depth for triangles, speed_accuracy_lines_* for lines.
std::string overview_name(const SceneSetRun& run, bool coverage) {
  return std::string("speed_accuracy_") + (run.name == "lines" ? "lines_" : "") + (coverage ? "coverage" : "depth");
}

// One family's chart (both measures side by side): speed_accuracy_<set>_<family>, non-alphanumerics as '_'.
std::string family_chart_name(const SceneSetRun& run, const std::string& family) {
  std::string name = "speed_accuracy_" + run.name + "_";
  for (char c : family) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

std::string front_text(const SceneSetRun& run, const std::vector<FrontPoint>& front) {
  std::string text;
  for (const FrontPoint& p : front)
    text += (text.empty() ? "" : ", ") + run.entries[p.entry].method + " (#" + std::to_string(p.entry + 1) + ")" +
            (p.separated ? "" : " not separated");
  return text;
}

// The scalar entries a chart shows: one family's with the exact path's, or all (empty family).
std::vector<size_t> chart_members(const SceneSetRun& run, const std::string& family) {
  std::vector<size_t> members;
  for (size_t i = 0; i < run.entries.size(); ++i)
    if (run.entries[i].tier == Tier::Scalar &&
        (family.empty() || run.entries[i].family == family || run.entries[i].family == "exact path"))
      members.push_back(i);
  return members;
}

// Families in order of first appearance among `members`, the exact path first: one series each.
std::vector<std::string> series_of(const SceneSetRun& run, const std::vector<size_t>& members) {
  std::vector<std::string> families{"exact path"};
  for (size_t i : members)
    if (std::find(families.begin(), families.end(), run.entries[i].family) == families.end())
      families.push_back(run.entries[i].family);
  return families;
}

// Mismatch is often 0 (the exact path), and the rest spans decades (0.01% to 60%): a log axis with
// the 0 row at log_axis_floor, labelled "0" (gnuplot.hpp).
struct YAxis {
  double floor = 0.1, low = 0.05, high = 10;
};
YAxis y_axis_for(const SceneSetRun& run, const std::vector<size_t>& members, bool coverage) {
  std::vector<double> values;
  for (size_t i : members) values.push_back(mismatch_of(run.entries[i], coverage));
  YAxis axis;
  axis.floor = log_axis_floor(values);
  double top = axis.floor * 10;
  for (double v : values) top = std::max(top, v);
  axis.low = axis.floor / 2.5;
  axis.high = top * 4;
  return axis;
}

double shown_y(double value, const YAxis& axis) { return value > 0 ? value : axis.floor; }

// x spans every member's interval and the reference lines, with a margin, on a log axis.
std::pair<double, double> x_range_for(const SceneSetRun& run, const std::vector<size_t>& members) {
  double low = run.lavapipe.seconds_per_frame, high = low;
  for (const EntrySummary& e : run.entries)
    if (e.tier == Tier::Fast) {
      low = std::min(low, e.seconds_per_frame);
      high = std::max(high, e.seconds_per_frame);
    }
  for (size_t i : members) {
    low = std::min(low, run.entries[i].seconds_low);
    high = std::max(high, run.entries[i].seconds_high);
  }
  return {low / 1.6, high * 1.6};
}

constexpr const char* kFamilyColours[] = {"#000000", "#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd",
                                          "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};

// One panel: the members with horizontal 95% bars, the scalar-tier front through them (a filled
// disc where the front point's interval is clear of its neighbours', a ring where it overlaps one:
// "not separated"), the fast path's and lavapipe's medians as vertical reference lines, and each
// point's number from the page's table. Appends its data blocks; returns its gnuplot commands.
std::string panel(const SceneSetRun& run, const std::vector<size_t>& members, const std::vector<FrontPoint>& front,
                  bool coverage, const std::string& title, const std::string& x_label, std::vector<DataBlock>& blocks) {
  const YAxis y = y_axis_for(run, members, coverage);
  const auto [x_min, x_max] = x_range_for(run, members);
  std::vector<std::string> plots;
  const auto add_block = [&](DataBlock block, const std::string& style) {
    if (block.rows.size() <= 1) return;  // the header row alone: nothing to draw
    plots.push_back(fmt::format("DATA index {} {}", blocks.size(), style));
    blocks.push_back(std::move(block));
  };
  const auto xy = [&](const EntrySummary& e) {
    return std::vector<std::string>{fmt::format("{}", e.seconds_per_frame),
                                    fmt::format("{}", shown_y(mismatch_of(e, coverage), y))};
  };
  DataBlock line{"front", {{"x", "x", quoted("scalar-tier Pareto front")}}};
  DataBlock clear{"separated", {{"x", "x", quoted("front point, separated")}}};
  DataBlock overlapping{"not separated",
                        {{"x", "x", quoted("front point NOT separated (intervals overlap; see the page)")}}};
  for (const FrontPoint& p : front) {
    std::vector<std::string> row = xy(run.entries[p.entry]);
    row.push_back("x");
    line.rows.push_back(row);
    (p.separated ? clear : overlapping).rows.push_back(row);
  }
  add_block(line, "using 1:2 title columnheader(3) with lines lw 3 dt 1 lc rgb '#aaaaaa'");
  add_block(clear, "using 1:2 title columnheader(3) with points pt 7 ps 3.2 lc rgb '#555555'");
  add_block(overlapping, "using 1:2 title columnheader(3) with points pt 6 ps 3.4 lw 2 lc rgb '#d62728'");
  const std::vector<std::string> families = series_of(run, members);
  for (size_t f = 0; f < families.size(); ++f) {
    DataBlock block{families[f], {{"x", "x", quoted(families[f]), "x", "x"}}};
    for (size_t i : members)
      if (run.entries[i].family == families[f]) {
        std::vector<std::string> row = xy(run.entries[i]);
        row.push_back("x");
        row.push_back(fmt::format("{}", run.entries[i].seconds_low));
        row.push_back(fmt::format("{}", run.entries[i].seconds_high));
        block.rows.push_back(row);
      }
    add_block(block,
              fmt::format("using 1:2:4:5 title columnheader(3) with xerrorbars pt {} ps 1.3 lw 1.5 dt 1 lc rgb '{}'",
                          f == 0 ? 5 : 7 + 2 * int((f - 1) % 3), kFamilyColours[f % 10]));
  }
  // The other tiers: vertical lines at their medians (mismatch given in the title), not front members.
  const auto reference = [&](const EntrySummary& e, const std::string& name, const std::string& style) {
    DataBlock block{name, {{"x", "x", quoted(name)}}};
    block.rows.push_back({fmt::format("{}", e.seconds_per_frame), fmt::format("{}", y.low), "x"});
    block.rows.push_back({fmt::format("{}", e.seconds_per_frame), fmt::format("{}", y.high), "x"});
    add_block(block, "using 1:2 title columnheader(3) with lines " + style);
  };
  int dash = 2;
  for (const EntrySummary& e : run.entries)
    if (e.tier == Tier::Fast)
      reference(e, fmt::format("fast path {} (SIMD; {:g}% mismatch)", e.method, mismatch_of(e, coverage)),
                fmt::format("lw 2 dt {} lc rgb '#2ca02c'", dash++));
  reference(run.lavapipe, "lavapipe (the reference)", "lw 2 dt 1 lc rgb '#d62728'");

  std::vector<ChartPoint> points;
  for (size_t i : members)
    points.push_back(
        {run.entries[i].seconds_per_frame, std::log10(shown_y(mismatch_of(run.entries[i], coverage), y)), int(i + 1)});
  std::string labels;
  int tag = 1;
  for (const LabelCluster& c :
       cluster_labels(points, ChartAxes{true, x_min, x_max, std::log10(y.low), std::log10(y.high)}))
    labels += fmt::format("set label {} {} at first {}, first {} offset char 0.9,0.7 font ',9' front\n", tag++,
                          gp_quote(c.text), c.x, std::pow(10.0, c.y));
  std::string plot = "plot ";
  for (size_t k = 0; k < plots.size(); ++k) plot += (k ? ", \\\n     " : "") + plots[k];
  return fmt::format(
             "set title {}\nset logscale xy 10\nset xrange [{}:{}]\nset yrange [{}:{}]\n"
             "set format y '%g'\nset ytics auto\n{}set grid\n"
             "set xlabel {} offset 0,0.4\nset ylabel 'samples differing from lavapipe (%, log)'\nunset label\n",
             gp_quote(title), x_min, x_max, y.low, y.high, zero_tic_command("y", y.floor), gp_quote(x_label)) +
         labels + plot + "\n";
}

void overview_chart(const std::string& dir, const SceneSetRun& run, bool coverage, FrontClock clock) {
  const std::vector<size_t> members = chart_members(run, "");
  std::vector<DataBlock> blocks;
  const std::string body =
      "set key outside below center horizontal maxrows 4 font ',10'\n" +
      panel(run, members, scalar_front(run.entries, "", coverage), coverage,
            "Scalar tier, " + run.name + ": " + measure_name(coverage) + " mismatch (numbers: the page's table)",
            time_name(clock) + " per frame of the set (s, log; bars: 95% interval of the median)", blocks);
  render_chart(dir, overview_name(run, coverage), blocks, body);
}

void family_chart(const std::string& dir, const SceneSetRun& run, const std::string& family, FrontClock clock) {
  const std::vector<size_t> members = chart_members(run, family);
  std::vector<DataBlock> blocks;
  std::string body = fmt::format(
      "set multiplot layout 1,2 margins 0.08,0.98,0.30,0.90 spacing 0.08,0.1 title {} font ',13'\n"
      "set key at screen 0.5,0.01 center bottom horizontal maxrows 4 font ',10'\n",
      gp_quote(run.name + ": " + family +
               " against the exact path (scalar tier); bars: 95% interval of the median; "
               "numbers: the page's table"));
  const std::string x_label =
      (clock == FrontClock::Cpu ? "CPU time" : "wall time") + std::string(" per frame of the set (s, log)");
  body += panel(run, members, scalar_front(run.entries, family, true), true, measure_name(true) + " mismatch", x_label,
                blocks);
  body += "set key off\n" + panel(run, members, scalar_front(run.entries, family, false), false,
                                  measure_name(false) + " mismatch", x_label, blocks);
  body += "unset multiplot\n";
  render_chart(dir, family_chart_name(run, family), blocks, body);
}

// The page's table: each method's number on the charts, its times, spread and both mismatches.
std::vector<std::vector<std::string>> method_table(const SceneSetRun& run) {
  std::vector<std::vector<std::string>> table{{"#", "tier", "family", "method", "wall ms (median)", "95% interval (ms)",
                                               "spread", "CPU ms (median, clock)", "coverage mismatch %",
                                               "depth mismatch %"}};
  const auto row = [](const std::string& number, const EntrySummary& e) {
    return std::vector<std::string>{number,
                                    to_string(e.tier),
                                    e.family,
                                    e.method,
                                    fmt::format("{:.3f}", e.seconds_per_frame * 1e3),
                                    fmt::format("{:.3f} .. {:.3f}", e.seconds_low * 1e3, e.seconds_high * 1e3),
                                    fmt::format("{:.2f}", run_spread(e.wall_runs)),
                                    fmt::format("{:.3f} ({})", e.cpu_seconds * 1e3, e.cpu_clock),
                                    fmt::format("{:.4f}", e.coverage_mismatch_pct),
                                    fmt::format("{:.4f}", e.depth_mismatch_pct)};
  };
  for (size_t i = 0; i < run.entries.size(); ++i) table.push_back(row(std::to_string(i + 1), run.entries[i]));
  table.push_back(row("ref", run.lavapipe));
  return table;
}

std::vector<std::vector<std::string>> fronts_table(const SceneSetRun& run) {
  std::vector<std::vector<std::string>> table{
      {"family", "measure", "scalar-tier front (fastest first; # as in the table above)", "points"}};
  std::vector<std::string> families = scalar_families(run.entries);
  families.insert(families.begin(), "");
  for (const std::string& family : families)
    for (bool coverage : {true, false}) {
      const std::vector<FrontPoint> front = scalar_front(run.entries, family, coverage);
      table.push_back({family.empty() ? "(all scalar entries)" : family, coverage ? "coverage" : "depth",
                       front_text(run, front), std::to_string(front.size())});
    }
  return table;
}

nlohmann::ordered_json entry_json(const EntrySummary& e) {
  return nlohmann::ordered_json{{"family", e.family},
                                {"method", e.method},
                                {"tier", to_string(e.tier)},
                                {"seconds_per_frame", e.seconds_per_frame},
                                {"seconds_ci_low", e.seconds_low},
                                {"seconds_ci_high", e.seconds_high},
                                {"ci_coverage", e.ci_coverage},
                                {"seconds_spread", run_spread(e.wall_runs)},
                                {"cpu_clock", e.cpu_clock},
                                {"cpu_seconds_per_frame", e.cpu_seconds},
                                {"cpu_seconds_ci_low", e.cpu_seconds_low},
                                {"cpu_seconds_ci_high", e.cpu_seconds_high},
                                {"cpu_seconds_spread", run_spread(e.cpu_runs)},
                                {"coverage_mismatch_pct", e.coverage_mismatch_pct},
                                {"depth_mismatch_pct", e.depth_mismatch_pct},
                                {"seconds_runs", e.wall_runs},
                                {"cpu_seconds_runs", e.cpu_runs}};
}

nlohmann::ordered_json front_json(const SceneSetRun& run, const std::vector<FrontPoint>& front) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const FrontPoint& p : front)
    out.push_back({{"entry", run.entries[p.entry].family + ": " + run.entries[p.entry].method},
                   {"number", p.entry + 1},
                   {"separated", p.separated}});
  return out;
}

}  // namespace

std::string speed_accuracy_json(const SpeedAccuracyRun& run) {
  nlohmann::ordered_json out;
  out["host"] = run.host.host;
  out["cpu_model"] = run.host.cpu_model;
  out["git_commit"] = run.host.git_commit;
  out["git_dirty"] = run.host.git_dirty;
  out["load_average_1min_before"] = run.host.load_before;
  out["load_average_1min_after"] = run.host.load_after;
  out["freed_memory_kept"] = run.host.freed_memory_kept;
  out["repeats"] = run.repeats;
  out["fronts"] =
      "scalar tier only (the exact path and the classic methods); the fast path and lavapipe are references";
  out["front_clock"] = to_string(run.clock);  // which median and interval rank the fronts and mark separation
  out["sets"] = nlohmann::ordered_json::array();
  for (const SceneSetRun& set : run.sets) {
    nlohmann::ordered_json s;
    s["scene_set"] = set.name;
    s["lavapipe"] = entry_json(set.lavapipe);
    s["methods"] = nlohmann::ordered_json::array();
    for (const EntrySummary& e : set.entries) s["methods"].push_back(entry_json(e));
    s["left_out"] = nlohmann::ordered_json::array();
    for (const auto& [entry, why] : set.left_out) s["left_out"].push_back({{"entry", entry}, {"why", why}});
    const SceneSetRun by_clock = ranked(set, run.clock);
    for (bool coverage : {true, false}) {
      const std::string measure = coverage ? "coverage" : "depth";
      s["pareto_front_" + measure] = front_json(set, scalar_front(by_clock.entries, "", coverage));
      nlohmann::ordered_json families = nlohmann::ordered_json::object();
      for (const std::string& family : scalar_families(set.entries))
        families[family] = front_json(set, scalar_front(by_clock.entries, family, coverage));
      s["family_fronts_" + measure] = families;
      // Across tiers, for the one question it answers: does a classic method beat the fast path at all?
      nlohmann::ordered_json cross = nlohmann::ordered_json::object();
      for (const auto& [family, indices] : family_pareto_fronts(by_clock.entries, coverage)) {
        cross[family] = nlohmann::ordered_json::array();
        for (size_t i : indices) cross[family].push_back(set.entries[i].family + ": " + set.entries[i].method);
      }
      s["cross_tier_family_fronts_" + measure] = cross;
    }
    out["sets"].push_back(s);
  }
  return out.dump(2) + "\n";
}

void write_speed_accuracy_outputs(const std::string& dir, const SpeedAccuracyRun& run) {
  const std::string json = speed_accuracy_json(run);
  write_json_file(dir, "speed_accuracy.json", json);
  write_speed_accuracy_tables(dir, json);
  std::vector<PageSection> sections;
  sections.push_back({"Run",
                      fmt::format("Host {}, {}; commit {}{}; 1-minute load average {:.2f} before the timed "
                                  "repetitions and {:.2f} after; {} interleaved repetitions; fronts and charts on {}.",
                                  run.host.host, run.host.cpu_model, run.host.git_commit,
                                  run.host.git_dirty ? " with uncommitted changes" : "", run.host.load_before,
                                  run.host.load_after, run.repeats, time_name(run.clock)),
                      {}});
  for (const SceneSetRun& set : run.sets) {
    const SceneSetRun by_clock = ranked(set, run.clock);
    overview_chart(dir, by_clock, true, run.clock);
    overview_chart(dir, by_clock, false, run.clock);
    const std::string scenes = set.name == "lines"
                                   ? "64 one-pixel lines radiating in a 256x256 frame; 64 lines crossing its edges"
                                   : "coplanar pair, house, sliver pair, mesh";
    std::string left_out;
    for (const auto& [entry, why] : set.left_out) left_out += " Left out: " + entry + " (" + why + ").";
    sections.push_back(
        {"Scalar tier, coverage, " + set.name,
         "The exact path and every classic method over the scene set (" + scenes + "): the median " +
             time_name(run.clock) + " per frame over " + std::to_string(run.repeats) +
             " interleaved repetitions, with the order-statistics 95% interval of the median as an error bar, against "
             "the share of samples whose owner differs from lavapipe (log axis; the row labelled 0 holds the exact "
             "matches). Grey: the Pareto front among these scalar-tier entries; a red ring marks a front point whose "
             "interval overlaps its front neighbour's or an equally accurate entry's, so the run does not establish "
             "it. Green dashed: "
             "the fast path (SIMD and threads, another tier), red: lavapipe; both are references, not front members. "
             "The table gives both clocks; spread: (max - min) / median of the repetitions' wall times." +
             left_out,
         {overview_name(set, true)},
         method_table(set)});
    sections.push_back({"Scalar tier, depth, " + set.name,
                        "The same runs, judged on the raw stored depth.",
                        {overview_name(set, false)}});
    for (const std::string& family : scalar_families(set.entries)) {
      family_chart(dir, by_clock, family, run.clock);
      sections.push_back({set.name + ": " + family,
                          "The family's methods with the exact path; left coverage, right depth. Coverage front: " +
                              front_text(set, scalar_front(by_clock.entries, family, true)) +
                              ". Depth front: " + front_text(set, scalar_front(by_clock.entries, family, false)) + ".",
                          {family_chart_name(set, family)}});
    }
    sections.push_back({"Scalar-tier fronts, " + set.name,
                        "A method is on a front when no other scalar-tier method is both faster (median " +
                            time_name(run.clock) + ") and closer to lavapipe.",
                        {},
                        fronts_table(by_clock)});
  }
  write_index_html(dir, "Speed against accuracy", sections, {kSpeedAccuracyCsv, "speed_accuracy.json"});
}

}  // namespace rastercmp::experiments
