#include "experiments/summary_figure.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "experiments/doc_table_renderers.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/html_page.hpp"
#include "model/errors.hpp"
#include "model/file_read.hpp"

namespace rastercmp::experiments {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::json;

// One file's JSON and where a field sits in it, for messages.
class Fields {
 public:
  explicit Fields(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& path, const std::string& expected, const Json& found) const {
    throw InputError(file_, path,
                     fmt::format("expected {}, found {}", expected, found.is_null() ? std::string("nothing") : found.dump()));
  }
  const Json& member(const Json& object, const std::string& path, const std::string& key) const {
    if (!object.is_object()) fail(path, "an object", object);
    if (!object.contains(key)) throw InputError(file_, path + "." + key, "expected this field, found none");
    return object.at(key);
  }
  const Json& array(const Json& object, const std::string& path, const std::string& key) const {
    const Json& v = member(object, path, key);
    if (!v.is_array()) fail(path + "." + key, "an array", v);
    return v;
  }
  std::string text(const Json& object, const std::string& path, const std::string& key) const {
    const Json& v = member(object, path, key);
    if (!v.is_string()) fail(path + "." + key, "a string", v);
    return v.get<std::string>();
  }
  // A number, or NaN for null when `nullable`.
  double number(const Json& object, const std::string& path, const std::string& key, bool nullable) const {
    const Json& v = member(object, path, key);
    if (v.is_number()) return v.get<double>();
    if (nullable && v.is_null()) return NAN;
    fail(path + "." + key, nullable ? "a number or null" : "a number", v);
  }
  bool boolean(const Json& object, const std::string& path, const std::string& key, bool nullable) const {
    const Json& v = member(object, path, key);
    if (v.is_boolean()) return v.get<bool>();
    if (nullable && v.is_null()) return false;
    fail(path + "." + key, nullable ? "true, false or null" : "true or false", v);
  }

 private:
  std::string file_;
};

std::string item(const std::string& key, size_t i) { return fmt::format("$.{}[{}]", key, i); }

std::vector<SummaryRow> read_stability(const Fields& f, const Json& root) {
  std::vector<SummaryRow> rows;
  const Json& list = f.array(root, "$", "boundaries");
  for (size_t i = 0; i < list.size(); ++i) {
    const Json& b = list[i];
    const std::string path = item("boundaries", i);
    if (!b.is_object()) f.fail(path, "an object", b);
    if (!b.contains("predicted") || b["predicted"].is_null()) continue;  // a series without a prediction
    const double predicted = f.number(b, path, "predicted", false);
    const double low = f.number(b, path, "measured_low", true), high = f.number(b, path, "measured_high", true);
    if (std::isnan(high) && std::isnan(low)) continue;  // never failed in its range: no bracket
    SummaryRow row{"stability.json", f.text(b, path, "family"),
                   f.text(b, path, "experiment") + " " + f.text(b, path, "case") + " " + f.text(b, path, "method")};
    row.low = (std::isnan(low) ? high : low) / predicted;
    row.high = (std::isnan(high) ? low : high) / predicted;
    row.agrees = f.boolean(b, path, "predicted_in_bracket", false);
    rows.push_back(row);
  }
  return rows;
}

std::vector<SummaryRow> read_zfight(const Fields& f, const Json& root) {
  std::vector<SummaryRow> rows;
  const Json& list = f.array(root, "$", "series");
  for (size_t i = 0; i < list.size(); ++i) {
    const Json& s = list[i];
    const std::string path = item("series", i);
    const double predicted = f.number(s, path, "predicted_onset", true);
    const double above = f.number(s, path, "measured_onset_above", true);
    const double at_most = f.number(s, path, "measured_onset_at_most", true);
    if (std::isnan(predicted) || (std::isnan(above) && std::isnan(at_most))) continue;  // no onset to compare
    const Json& interval = f.array(s, path, "predicted_onset_interval");
    if (interval.size() != 2 || !interval[0].is_number() || !interval[1].is_number())
      f.fail(path + ".predicted_onset_interval", "two numbers", interval);
    const bool calibration = s.contains("calibration") && s["calibration"].is_boolean() && s["calibration"].get<bool>();
    SummaryRow row{"zfight.json", "z-fighting (model)",
                   f.text(s, path, "format") + " " + f.text(s, path, "mapping") + (calibration ? " (calibration)" : "")};
    row.low = (std::isnan(above) ? at_most : above) / predicted;
    row.high = (std::isnan(at_most) ? above : at_most) / predicted;
    row.predicted_low = interval[0].get<double>() / predicted;
    row.predicted_high = interval[1].get<double>() / predicted;
    row.agrees = f.boolean(s, path, "agrees", true);
    rows.push_back(row);
  }
  return rows;
}

std::vector<SummaryRow> read_depth_r(const Fields& f, const Json& root) {
  std::vector<SummaryRow> rows;
  if (!root.is_array()) f.fail("$", "an array of formats", root);
  for (size_t i = 0; i < root.size(); ++i) {
    const std::string path = fmt::format("$[{}]", i);
    const double predicted = f.number(root[i], path, "predicted", false);
    const double cpu = f.number(root[i], path, "r_cpu", false), vk = f.number(root[i], path, "r_vulkan", false);
    SummaryRow row{"depth_r.json", "polygon offset r", f.text(root[i], path, "format") + " r (CPU, Vulkan)"};
    row.low = std::min(cpu, vk) / predicted;
    row.high = std::max(cpu, vk) / predicted;
    row.agrees = std::fabs(row.low - 1) <= 1e-3 && std::fabs(row.high - 1) <= 1e-3;
    rows.push_back(row);
  }
  return rows;
}

std::vector<SummaryRow> read_depth_precision(const Fields& f, const Json& root) {
  std::vector<SummaryRow> rows;
  const Json& list = f.array(root, "$", "series");
  for (size_t i = 0; i < list.size(); ++i) {
    const Json& s = list[i];
    const std::string path = item("series", i);
    const double low = f.number(s, path, "measured_over_ideal_min", true);
    const double high = f.number(s, path, "measured_over_ideal_max", true);
    if (std::isnan(low) || std::isnan(high)) continue;
    SummaryRow row{"depth_precision.json", "depth precision",
                   f.text(s, path, "format") + " " + f.text(s, path, "mapping") + " bucket"};
    row.low = low;
    row.high = high;
    row.agrees = f.number(s, path, "agree", false) ==
                 f.number(s, path, "points", false) - f.number(s, path, "open_buckets", false);
    rows.push_back(row);
  }
  return rows;
}

std::vector<SummaryRow> read_resolution(const Fields& f, const Json& root) {
  std::vector<SummaryRow> rows;
  const Json& list = f.array(root, "$", "methods");
  for (size_t i = 0; i < list.size(); ++i) {
    const Json& m = list[i];
    const std::string path = item("methods", i);
    const double measured = f.number(m, path, "measured_exponent", true);
    if (std::isnan(measured)) continue;  // no mismatch at two sizes or more
    const double predicted = f.number(m, path, "predicted_exponent", false);
    SummaryRow row{"resolution.json", "error growth with size", f.text(m, path, "method") + " exponent"};
    row.low = row.high = measured / predicted;
    row.agrees = f.boolean(m, path, "agrees", true);
    rows.push_back(row);
  }
  return rows;
}

void chart_summary(const std::string& dir, const std::vector<SummaryRow>& rows) {
  std::vector<DataBlock> blocks;
  std::vector<std::string> sources;
  for (const SummaryRow& r : rows)
    if (std::find(sources.begin(), sources.end(), r.source) == sources.end()) sources.push_back(r.source);
  double lo = 1, hi = 1;
  for (size_t s = 0; s < sources.size(); ++s) {
    DataBlock block{sources[s], {}};
    for (size_t i = 0; i < rows.size(); ++i) {
      const SummaryRow& r = rows[i];
      if (r.source != sources[s]) continue;
      lo = std::min({lo, r.low, r.predicted_low});
      hi = std::max({hi, r.high, r.predicted_high});
      // y (top row first), the bracket's middle, low, high, the prediction's interval, agrees, label
      const double y = double(rows.size() - 1 - i);
      block.rows.push_back({num(y), num(std::sqrt(r.low * r.high)), num(r.low), num(r.high), num(r.predicted_low),
                            num(r.predicted_high), r.agrees ? "1" : "0",
                            "\"" + r.family + ": " + r.label + "\""});
    }
    blocks.push_back(block);
  }
  std::string plot;
  for (size_t s = 0; s < sources.size(); ++s)
    plot += fmt::format(
        "{}DATA index {} using 2:1:3:4:ytic(8) with xerrorbars lt {} pt 7 ps 1.2 lw 2 title {}, "
        "DATA index {} using ($7 == 0 ? $2 : NaN):1 with points pt 6 ps 2.6 lw 2 lc rgb '#000000' notitle, "
        "DATA index {} using (($5 != 1 || $6 != 1) ? 1 : NaN):($1 - 0.3):5:6 with xerrorbars pt 2 ps 0.8 "
        "lc rgb '#555555' notitle",
        s ? ", \\\n  " : "", s, s + 1, gp_quote(sources[s]), s, s);
  plot += ", \\\n  NaN with points pt 6 ps 2.6 lw 2 lc rgb '#000000' title 'prediction outside the measured bracket'"
          ", \\\n  NaN with xerrorbars pt 2 lc rgb '#555555' title 'the prediction''s own interval (z-fighting)'";
  const std::string body = fmt::format(
      "set title 'Measured boundaries against their predictions (bar: measured bracket / prediction; 1: agreement)'\n"
      "set termoption noenhanced\nset logscale x\nset format x '%g'\nset xrange [{}:{}]\nset yrange [-1:{}]\n"
      "set ytics font ',10'\nset grid xtics\nset lmargin 62\n"
      "set xlabel 'measured / predicted (log scale)'\n"
      "set arrow from 1, graph 0 to 1, graph 1 nohead dt 2 lw 2 lc rgb '#444444'\n"
      "set key outside below maxrows 3 font ',10'\n"
      "plot {}\n",
      num(lo / 2), num(hi * 2), rows.size(), plot);
  render_chart_sized(dir, "summary_boundaries", blocks, body, 1400, int(260 + 22 * rows.size()));
}

}  // namespace

std::vector<SummaryRow> read_summary_file(const std::string& path) {
  const std::string name = fs::path(path).filename().string();
  Json root;
  try {
    root = Json::parse(read_bounded_file(path, 256ull << 20, "an experiment's JSON output"));
  } catch (const Json::parse_error& e) {
    throw InputError(path, "", fmt::format("expected JSON, found a parse error ({})", e.what()));
  }
  const Fields f(path);
  if (name == "stability.json") return read_stability(f, root);
  if (name == "zfight.json") return read_zfight(f, root);
  if (name == "depth_r.json") return read_depth_r(f, root);
  if (name == "depth_precision.json") return read_depth_precision(f, root);
  if (name == "resolution.json") return read_resolution(f, root);
  throw InputError(path, "", "expected stability.json, zfight.json, depth_r.json, depth_precision.json or resolution.json");
}

std::vector<SummaryRow> read_summary_inputs(const std::vector<std::string>& dirs) {
  std::vector<SummaryRow> rows;
  for (const std::string& dir : dirs) {
    bool any = false;
    for (const char* name : kSummaryInputs) {
      const fs::path path = fs::path(dir) / name;
      if (!fs::is_regular_file(path)) continue;
      any = true;
      for (SummaryRow& r : read_summary_file(path.string())) rows.push_back(std::move(r));
    }
    if (!any)
      throw UsageError(fmt::format("chart summary --from {}: holds none of stability.json, zfight.json, depth_r.json, "
                                   "depth_precision.json, resolution.json",
                                   dir));
  }
  return rows;
}

std::vector<std::string> default_summary_dirs() {
  std::vector<std::string> dirs;
  for (const char* dir : {"sweep-stability", "sweep-zfight", "sweep-polygon-offset", "chart-depth-precision",
                          "chart-resolution"})
    if (fs::is_directory(dir)) dirs.push_back(dir);
  return dirs;
}

void run_summary(const SweepOptions& options, const std::vector<std::string>& from_dirs) {
  const std::vector<std::string> dirs = from_dirs.empty() ? default_summary_dirs() : from_dirs;
  if (dirs.empty())
    throw UsageError(
        "chart summary: no --from folder, and none of the default output folders (sweep-stability, sweep-zfight, "
        "sweep-polygon-offset, chart-depth-precision, chart-resolution) is in the working directory; run those "
        "commands first or name their folders with --from");
  const std::vector<SummaryRow> rows = read_summary_inputs(dirs);
  if (rows.empty())
    throw UsageError(fmt::format("chart summary: the files in {} hold no boundary with a prediction", fmt::join(dirs, ", ")));
  find_gnuplot();
  prepare_out_dir(options.out_dir);
  nlohmann::ordered_json json;
  json["from"] = dirs;
  json["rows"] = nlohmann::ordered_json::array();
  std::vector<std::vector<std::string>> table{
      {"source", "family", "boundary", "measured / predicted", "prediction's interval", "agrees"}};
  size_t agree = 0;
  for (const SummaryRow& r : rows) {
    json["rows"].push_back({{"source", r.source},
                            {"family", r.family},
                            {"label", r.label},
                            {"measured_over_predicted_low", r.low},
                            {"measured_over_predicted_high", r.high},
                            {"predicted_interval_low", r.predicted_low},
                            {"predicted_interval_high", r.predicted_high},
                            {"agrees", r.agrees}});
    agree += r.agrees ? 1 : 0;
    table.push_back({r.source, r.family, r.label,
                     r.low == r.high ? fmt::format("{:.3g}", r.low) : fmt::format("{:.3g} .. {:.3g}", r.low, r.high),
                     r.predicted_low == r.predicted_high ? "—"
                                                         : fmt::format("{:.3g} .. {:.3g}", r.predicted_low, r.predicted_high),
                     r.agrees ? "yes" : "no"});
  }
  json["agree"] = agree;
  write_json_file(options.out_dir, "summary.json", json.dump(2) + "\n");
  write_summary_tables(options.out_dir, json.dump());
  chart_summary(options.out_dir, rows);
  write_index_html(
      options.out_dir, "Measured boundaries against their predictions",
      {{"All boundaries",
        fmt::format("Read from {}. Each bar is the measured bracket divided by the prediction (a point: one measured "
                    "value); 1 is agreement. A black ring marks a row whose source says the prediction is not met. "
                    "{} of {} rows agree.",
                    fmt::join(dirs, ", "), agree, rows.size()),
        {"summary_boundaries"},
        table}},
      {"summary.json"});
}

}  // namespace rastercmp::experiments
