#include "experiments/doc_table_renderers.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "experiments/doc_tables.hpp"

namespace rastercmp::experiments {
namespace {

using Json = nlohmann::json;
const ColumnSpec kExact{ColumnKind::Exact, ""};
const ColumnSpec kHost{ColumnKind::Host, ""};

double value_of(const Json& v) { return v.is_number() ? v.get<double>() : NAN; }
std::string cell(const Json& v) { return table_value(value_of(v)); }
std::string fixed(const Json& v, int digits) {
  const double d = value_of(v);
  return std::isnan(d) ? "—" : fmt::format("{:.{}f}", d, digits);
}
std::string yes_no(const Json& v) { return v.is_boolean() ? (v.get<bool>() ? "yes" : "**no**") : "—"; }

std::string join(const std::vector<std::string>& items, const std::string& sep) {
  std::string s;
  for (size_t i = 0; i < items.size(); ++i) s += (i ? sep : "") + items[i];
  return s;
}

void add_unique(std::vector<std::string>& list, const std::string& item) {
  if (std::find(list.begin(), list.end(), item) == list.end()) list.push_back(item);
}

MarkdownTable exact_table(std::vector<std::string> header) {
  MarkdownTable t;
  t.columns.assign(header.size(), kExact);
  t.header = std::move(header);
  return t;
}

}  // namespace

std::string table_value(double value) {
  if (std::isnan(value)) return "—";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (std::fabs(value) >= 1000 && std::fabs(value) < 1e12) {
    const long long n = std::llround(value);
    std::string digits = std::to_string(std::llabs(n)), out;
    for (size_t i = 0; i < digits.size(); ++i) {
      if (i && (digits.size() - i) % 3 == 0) out += ',';
      out += digits[i];
    }
    return (n < 0 ? "-" : "") + out;
  }
  return fmt::format("{:.3g}", value);
}

void write_depth_r_tables(const std::string& dir, const std::string& depth_r_json) {
  MarkdownTable t = exact_table({"format", "raw step (CPU, Vulkan)", "r (CPU)", "r (Vulkan)", "spec bound",
                                 "r / spec bound", "r / lavapipe's predicted r"});
  for (const Json& f : Json::parse(depth_r_json))
    t.rows.push_back({f["format"].get<std::string>(), cell(f["raw_step_cpu"]) + ", " + cell(f["raw_step_vulkan"]),
                      fmt::format("{:.6g}", value_of(f["r_cpu"])), fmt::format("{:.6g}", value_of(f["r_vulkan"])),
                      fmt::format("{:.6g}", value_of(f["spec_bound"])),
                      fmt::format("{:.8f}", value_of(f["r_over_spec_bound"])),
                      fmt::format("{:.8f}", value_of(f["measured_over_predicted"]))});
  write_markdown_table(dir, "depth-r", t);
}

void write_polygon_offset_tables(const std::string& dir, const std::string& polygon_offset_json) {
  // The identical-vertex control per format and constant: how many angles, the lost fractions seen.
  struct Group {
    int points = 0, expected = 0, agree = 0;
    std::vector<std::string> cpu, vk;
  };
  std::vector<std::pair<std::string, Group>> groups;
  const Json controls = Json::parse(polygon_offset_json);
  for (const Json& c : controls["identical_vertex_control"]) {
    const std::string key = c["format"].get<std::string>() + "\t" + table_value(value_of(c["constant"]));
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == key; });
    if (it == groups.end()) it = groups.insert(groups.end(), {key, Group{}});
    Group& g = it->second;
    ++g.points;
    g.expected += c["as_expected"].get<bool>();
    g.agree += c["cpu_vk_agree"].get<bool>();
    add_unique(g.cpu, cell(c["wrong_cpu"]));
    add_unique(g.vk, cell(c["wrong_vulkan"]));
  }
  MarkdownTable t = exact_table({"format", "constant (r)", "angles", "as expected", "exact path = lavapipe",
                                 "lost fraction (CPU)", "lost fraction (Vulkan)"});
  for (const auto& [key, g] : groups) {
    const size_t tab = key.find('\t');
    t.rows.push_back({key.substr(0, tab), key.substr(tab + 1), std::to_string(g.points), std::to_string(g.expected),
                      std::to_string(g.agree), join(g.cpu, ", "), join(g.vk, ", ")});
  }
  write_markdown_table(dir, "identical-vertex", t);
}

void write_zfight_tables(const std::string& dir, const std::string& zfight_json) {
  const Json r = Json::parse(zfight_json);
  MarkdownTable run = exact_table({"model", "size", "far", "target distance", "jitters", "calibrated gap"});
  const Json& gap = r["calibrated_gap_interval"];
  run.rows.push_back({std::filesystem::path(r["model"].get<std::string>()).filename().string(),
                      fmt::format("{}x{}", r["width"].get<int>(), r["height"].get<int>()), cell(r["far"]),
                      cell(r["target_distance"]), std::to_string(r["jitters"].get<int>()),
                      gap.is_array() ? cell(gap[0]) + " to " + cell(gap[1]) : "none"});
  write_markdown_table(dir, "zfight-run", run);

  MarkdownTable t =
      exact_table({"series", "measured onset: above, at most", "predicted onset interval", "agrees"});
  for (const Json& s : r["series"]) {
    const Json& p = s["predicted_onset_interval"];
    std::string predicted = p.is_array() && p[0].is_number() ? "[" + cell(p[0]) + ", " + cell(p[1]) + "]"
                                                             : std::string("none in the range");
    if (s["calibration"].get<bool>()) predicted += " (calibration)";
    auto onset = [](const Json& v) { return v.is_number() ? table_value(v.get<double>()) : std::string("none"); };
    t.rows.push_back({s["format"].get<std::string>() + ", " + s["mapping"].get<std::string>(),
                      onset(s["measured_onset_above"]) + ", " + onset(s["measured_onset_at_most"]), predicted,
                      yes_no(s["agrees"])});
  }
  write_markdown_table(dir, "zfight-series", t);
}

// Where a timed run took place (host columns: not compared), whether the allocator kept freed
// memory ("—" in a run that did not record it) and how many repetitions it took.
MarkdownTable run_table(const Json& r) {
  MarkdownTable run =
      exact_table({"host", "CPU", "commit", "load before", "load after", "freed memory kept", "repetitions"});
  run.columns = {kHost, kHost, kHost, kHost, kHost, kHost, kExact};
  run.rows.push_back({r["host"].get<std::string>(), r["cpu_model"].get<std::string>(),
                      r["git_commit"].get<std::string>().substr(0, 7) + (r["git_dirty"].get<bool>() ? " (dirty)" : ""),
                      fixed(r["load_average_1min_before"], 2), fixed(r["load_average_1min_after"], 2),
                      yes_no(r.contains("freed_memory_kept") ? r["freed_memory_kept"] : Json()),
                      std::to_string(r["repeats"].get<int>())});
  return run;
}

void write_speed_accuracy_tables(const std::string& dir, const std::string& speed_accuracy_json) {
  const Json r = Json::parse(speed_accuracy_json);
  MarkdownTable run = run_table(r);
  run.header.push_back("fronts on");
  run.columns.push_back(kExact);
  run.rows[0].push_back(r["front_clock"].get<std::string>() + " time");
  write_markdown_table(dir, "speed-accuracy-run", run);

  for (const Json& set : r["sets"]) {
    MarkdownTable t = exact_table({"#", "tier", "family", "method", "CPU ms (median)", "95% interval",
                                   "wall ms (median)", "wall spread", "coverage %", "depth %"});
    t.columns = {kExact, kExact, kExact, kExact, {ColumnKind::Timed, "95% interval"}, kHost, kHost, kHost,
                 kExact, kExact};
    auto row = [&](const std::string& number, const Json& e) {
      auto ms = [&](const char* key) { return fmt::format("{:.3f}", value_of(e[key]) * 1000); };
      t.rows.push_back({number, e["tier"].get<std::string>(), e["family"].get<std::string>(),
                        e["method"].get<std::string>(), ms("cpu_seconds_per_frame"),
                        ms("cpu_seconds_ci_low") + " .. " + ms("cpu_seconds_ci_high"), ms("seconds_per_frame"),
                        fixed(e["seconds_spread"], 2), fixed(e["coverage_mismatch_pct"], 4),
                        fixed(e["depth_mismatch_pct"], 4)});
    };
    row("ref", set["lavapipe"]);
    for (size_t i = 0; i < set["methods"].size(); ++i) row(std::to_string(i + 1), set["methods"][i]);
    write_markdown_table(dir, "speed-accuracy-" + set["scene_set"].get<std::string>(), t);
  }
}

void write_stability_tables(const std::string& dir, const std::string& stability_json) {
  const Json r = Json::parse(stability_json);

  // fight_onset: a row per (format, separation), a column per clip-z mapping.
  std::vector<std::string> mappings, rows;
  std::map<std::string, std::map<std::string, std::string>> cells;
  std::map<std::string, std::string> predicted;
  for (const Json& s : r["fight_onset"]) {
    const std::string mapping = s["mapping"].get<std::string>();
    const std::string row = s["format"].get<std::string>() + "\t" + cell(s["separation"]);
    add_unique(mappings, mapping);
    add_unique(rows, row);
    const int never = s["never"].get<int>(), jitters = s["jitters"].get<int>();
    std::string text;
    if (never == jitters) {
      text = "never";
    } else if (never == 0 && s["onset_min"] == s["onset_max"]) {
      text = cell(s["onset_min"]) + " (all)";
    } else {
      text = cell(s["onset_min"]) + " / " + cell(s["onset_median"]) + " / " +
             (never ? fmt::format("never ({} of {})", never, jitters) : cell(s["onset_max"]));
    }
    cells[row][mapping] = text;
    if (s["predicted"].is_number()) predicted[row] = cell(s["predicted"]);
  }
  std::vector<std::string> header = {"format", "separation", "predicted"};
  header.insert(header.end(), mappings.begin(), mappings.end());
  MarkdownTable onset = exact_table(header);
  for (const std::string& row : rows) {
    const size_t tab = row.find('\t');
    std::vector<std::string> line = {row.substr(0, tab), row.substr(tab + 1),
                                     predicted.count(row) ? predicted[row] : "none"};
    for (const std::string& m : mappings) line.push_back(cells[row].count(m) ? cells[row][m] : "—");
    onset.rows.push_back(line);
  }
  write_markdown_table(dir, "stability-fight-onset", onset);

  // Boundaries: series that fail (or refuse) somewhere; methods with the same bracket within one
  // case share a row, then cases with the same methods and bracket.
  struct Line {
    std::string experiment, cases, methods, last_clean, first_failing, failing;
  };
  std::vector<Line> by_case;
  for (const Json& b : r["boundaries"]) {
    const int failing = b["failing"].get<int>(), refused = b["refused"].get<int>();
    if (failing == 0 && refused == 0) continue;
    Line l{b["experiment"].get<std::string>(), b["case"].get<std::string>(), b["method"].get<std::string>(),
           cell(b["last_clean"]), b["boundary"].is_number() ? cell(b["boundary"]) : std::string("never"),
           fmt::format("{}/{}", failing, b["points"].get<int>()) +
               (refused ? fmt::format(" ({} refused)", refused) : std::string())};
    auto same = std::find_if(by_case.begin(), by_case.end(), [&](const Line& o) {
      return o.experiment == l.experiment && o.cases == l.cases && o.last_clean == l.last_clean &&
             o.first_failing == l.first_failing && o.failing == l.failing;
    });
    if (same == by_case.end()) by_case.push_back(l);
    else same->methods += ", " + l.methods;
  }
  std::vector<Line> merged;
  for (const Line& l : by_case) {
    auto same = std::find_if(merged.begin(), merged.end(), [&](const Line& o) {
      return o.experiment == l.experiment && o.methods == l.methods && o.last_clean == l.last_clean &&
             o.first_failing == l.first_failing && o.failing == l.failing;
    });
    if (same == merged.end()) merged.push_back(l);
    else same->cases += ", " + l.cases;
  }
  // A row that holds every case of its experiment says so instead of listing them.
  std::map<std::string, std::vector<std::string>> cases_of;
  for (const Json& b : r["boundaries"]) add_unique(cases_of[b["experiment"].get<std::string>()], b["case"].get<std::string>());
  MarkdownTable bounds =
      exact_table({"experiment", "case", "method", "last clean", "first failing", "failing points"});
  for (const Line& l : merged) {
    const std::vector<std::string>& all = cases_of[l.experiment];
    const bool every = all.size() > 1 && l.cases == join(all, ", ");
    bounds.rows.push_back({l.experiment, every ? "every case" : l.cases, l.methods, l.last_clean, l.first_failing,
                           l.failing});
  }
  write_markdown_table(dir, "stability-boundaries", bounds);

  // How many predicted series hold their prediction in the measured bracket, per experiment.
  std::vector<std::string> experiments;
  std::map<std::string, std::pair<int, int>> count;
  auto tally = [&](const std::string& experiment, const Json& s) {
    if (!s.contains("predicted") || !s["predicted"].is_number()) return;
    add_unique(experiments, experiment);
    ++count[experiment].first;
    count[experiment].second += s["predicted_in_bracket"].is_boolean() && s["predicted_in_bracket"].get<bool>();
  };
  for (const Json& s : r["fight_onset"]) tally("fight_onset", s);
  for (const Json& b : r["boundaries"]) tally(b["experiment"].get<std::string>(), b);
  MarkdownTable pred = exact_table({"experiment", "predicted series", "prediction in the bracket"});
  int all = 0, in = 0;
  for (const std::string& e : experiments) {
    pred.rows.push_back({e, std::to_string(count[e].first), std::to_string(count[e].second)});
    all += count[e].first;
    in += count[e].second;
  }
  pred.rows.push_back({"all", std::to_string(all), std::to_string(in)});
  write_markdown_table(dir, "stability-predictions", pred);

  // The per-point theories (map_theory.hpp), per experiment: series, points, points where theory
  // and measurement agree, the points among them with a predicted count, and series that hold.
  struct Tally {
    int series = 0, points = 0, agreeing = 0, counted = 0, holding = 0;
  };
  std::vector<std::string> theory_order;
  std::map<std::string, Tally> theory;
  for (const Json& b : r["boundaries"]) {
    if (!b.contains("expected_points")) continue;
    const std::string experiment = b["experiment"].get<std::string>();
    add_unique(theory_order, experiment);
    Tally& t = theory[experiment];
    ++t.series;
    t.holding += b["expected_holds"].get<bool>();
    for (const Json& point : b["expected_points"]) {
      ++t.points;
      t.agreeing += point["agrees"].get<bool>();
      t.counted += point["agrees"].get<bool>() && point["predicted_coverage_mismatch"].is_number();
    }
  }
  MarkdownTable expect = exact_table(
      {"experiment", "series", "points", "points as theory says", "of them with a predicted count", "series that hold"});
  Tally total;
  for (const std::string& e : theory_order) {
    const Tally& t = theory[e];
    expect.rows.push_back({e, std::to_string(t.series), std::to_string(t.points), std::to_string(t.agreeing),
                           std::to_string(t.counted), std::to_string(t.holding)});
    total.series += t.series, total.points += t.points, total.agreeing += t.agreeing, total.counted += t.counted,
        total.holding += t.holding;
  }
  expect.rows.push_back({"all", std::to_string(total.series), std::to_string(total.points), std::to_string(total.agreeing),
                         std::to_string(total.counted), std::to_string(total.holding)});
  write_markdown_table(dir, "stability-expectations", expect);
}

void write_scene_needs_tables(const std::string& dir, const std::string& scene_needs_json) {
  const Json r = Json::parse(scene_needs_json);
  MarkdownTable suite = exact_table({"stage", "need it", "skip it"});
  const std::vector<std::pair<std::string, std::string>> stages = {
      {"clipping", "clipping"}, {"depth", "depth"}, {"bias", "bias"},
      {"msaa", "MSAA"},         {"lines", "lines"}, {"culling", "culling"}};
  for (const auto& [key, name] : stages)
    suite.rows.push_back({name, std::to_string(r["suite"][key]["needs"].get<int>()),
                          std::to_string(r["suite"][key]["skips"].get<int>())});
  suite.rows.push_back({"scenes", std::to_string(r["suite"]["scenes"].get<int>()), ""});
  write_markdown_table(dir, "scene-needs-suite", suite);
  write_markdown_table(dir, "skip-savings-run", run_table(r));

  MarkdownTable t = exact_table({"scene", "skipped stages", "skip turned off", "ms, skipped", "ms, done",
                                 "done / skipped", "95% interval"});
  t.columns = {kExact, kExact, kExact, kHost, kHost, {ColumnKind::Timed, "95% interval"}, kHost};
  for (const Json& s : r["savings"]) {
    const double low = value_of(s["ratio_ci_low"]), high = value_of(s["ratio_ci_high"]);
    const std::string ratio = fmt::format("{:.3f}", value_of(s["ratio"]));
    const bool apart = low > 1 || high < 1;  // the interval excludes 1: the skip measurably changes the time
    t.rows.push_back({s["scene"].get<std::string>(), s["stages"].get<std::string>(), s["skip"].get<std::string>(),
                      fixed(s["on_ms"], 2), fixed(s["off_ms"], 2), apart ? "**" + ratio + "**" : ratio,
                      fmt::format("{:.3f} .. {:.3f}", low, high)});
  }
  write_markdown_table(dir, "skip-savings", t);
}

void write_depth_precision_tables(const std::string& dir, const std::string& depth_precision_json) {
  const Json r = Json::parse(depth_precision_json);
  MarkdownTable t = exact_table({"format", "mapping", "points (open)", "within 10% of ideal",
                                 "measured / ideal: min", "median", "max", "render_cpu agrees"});
  for (const Json& s : r["series"])
    t.rows.push_back({s["format"].get<std::string>(), s["mapping"].get<std::string>(),
                      fmt::format("{} ({})", s["points"].get<int>(), s["open_buckets"].get<int>()),
                      std::to_string(s["agree"].get<int>()), cell(s["measured_over_ideal_min"]),
                      cell(s["measured_over_ideal_median"]), cell(s["measured_over_ideal_max"]),
                      yes_no(s["render_check_agrees"])});
  write_markdown_table(dir, "depth-precision", t);
}

void write_resolution_tables(const std::string& dir, const std::string& resolution_json) {
  const Json r = Json::parse(resolution_json);
  std::vector<std::string> header = {"family", "method", "predicted", "measured", "holds"};
  for (const Json& size : r["sizes"]) header.push_back(std::to_string(size.get<int>()));
  MarkdownTable t = exact_table(header);
  for (const Json& m : r["methods"]) {
    std::vector<std::string> row = {m["family"].get<std::string>(), m["method"].get<std::string>(),
                                    cell(m["predicted_exponent"]),
                                    m["measured_exponent"].is_number()
                                        ? fmt::format("{:.2f}", m["measured_exponent"].get<double>())
                                        : std::string("—"),
                                    m["refused"].get<bool>() ? "refused" : yes_no(m["agrees"])};
    if (m["agrees"].is_null() && !m["refused"].get<bool>()) {
      // No exponent: a method that differs at no size or at one size only (no slope to fit).
      size_t nonzero = 0;
      for (const Json& p : m["points"]) nonzero += value_of(p["either"]) > 0;
      row[4] = nonzero == 0 ? "differs at no size" : "differs at one size only";
    }
    std::map<int, std::string> counts;
    for (const Json& p : m["points"]) counts[p["size"].get<int>()] = cell(p["either"]);
    for (const Json& size : r["sizes"]) row.push_back(counts.count(size.get<int>()) ? counts[size.get<int>()] : "—");
    // Methods that measure the same on every size share a row.
    auto same = std::find_if(t.rows.begin(), t.rows.end(), [&](const std::vector<std::string>& o) {
      return o[0] == row[0] && std::equal(o.begin() + 2, o.end(), row.begin() + 2);
    });
    if (same == t.rows.end()) t.rows.push_back(row);
    else (*same)[1] += ", " + row[1];
  }
  write_markdown_table(dir, "resolution", t);
}

void write_summary_tables(const std::string& dir, const std::string& summary_json) {
  const Json r = Json::parse(summary_json);
  std::vector<std::string> keys;
  std::map<std::string, std::pair<int, int>> count;
  for (const Json& row : r["rows"]) {
    const std::string key = row["source"].get<std::string>() + "\t" + row["family"].get<std::string>();
    add_unique(keys, key);
    ++count[key].first;
    count[key].second += row["agrees"].get<bool>();
  }
  MarkdownTable t = exact_table({"source", "family", "rows", "agree"});
  int all = 0, agree = 0;
  for (const std::string& key : keys) {
    const size_t tab = key.find('\t');
    t.rows.push_back({key.substr(0, tab), key.substr(tab + 1), std::to_string(count[key].first),
                      std::to_string(count[key].second)});
    all += count[key].first;
    agree += count[key].second;
  }
  t.rows.push_back({"all", "", std::to_string(all), std::to_string(agree)});
  write_markdown_table(dir, "summary-families", t);
}

}  // namespace rastercmp::experiments
