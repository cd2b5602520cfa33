#include "experiments/model_zfight.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "experiments/csv_log.hpp"
#include "experiments/doc_table_renderers.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/html_page.hpp"
#include "experiments/progress.hpp"
#include "model/errors.hpp"
#include "model/mesh_import.hpp"
#include "model/scene_io.hpp"

namespace rastercmp::experiments {
namespace {

enum class Mapping { Standard, Reversed };
const char* mapping_name(Mapping m) { return m == Mapping::Standard ? "standard" : "reversed"; }

// Sub-pixel shifts of the view, in pixels (the first is none).
const std::vector<std::pair<double, double>> kJitters = {{0, 0}, {0.37, 0.11}, {-0.23, 0.41}, {0.13, -0.29}};

std::vector<double> far_near_ratios(bool quick) {
  std::vector<double> ratios;
  for (int k = quick ? 2 : 1; k <= 16; k += quick ? 2 : 1) ratios.push_back(std::pow(10.0, k / 2.0));
  return ratios;
}

// The imported scene with clip z for near f / ratio, the mapping and the jitter: x and y are the
// framing camera's (they do not depend on near and far), z from the eye distance w in double.
Scene variant(const Scene& base, double far_plane, double ratio, Mapping mapping, DepthFormat format,
              std::pair<double, double> jitter) {
  Scene scene = base;
  scene.camera.reset();
  scene.depth_format = format;
  scene.depth_clear = mapping == Mapping::Standard ? 1.0f : 0.0f;
  const double f = far_plane, n = far_plane / ratio;
  for (Draw& draw : scene.draws) {
    draw.state.depth.compare_op = mapping == Mapping::Standard ? CompareOp::Less : CompareOp::Greater;
    for (glm::vec4& p : draw.positions_clip) {
      const double d = p.w;
      const double z = mapping == Mapping::Standard ? f * (d - n) / (f - n) : n * (f - d) / (f - n);
      p.z = float(z);
      p.x = float(double(p.x) + jitter.first * 2.0 / scene.width * d);
      p.y = float(double(p.y) + jitter.second * 2.0 / scene.height * d);
    }
  }
  return scene;
}

// Share of the pixels covered in either render whose owner differs.
double owner_difference(const RenderResult& a, const RenderResult& b) {
  size_t covered = 0, differ = 0;
  for (size_t i = 0; i < a.owner.size(); ++i) {
    if (a.owner[i] == kOwnerBackground && b.owner[i] == kOwnerBackground) continue;
    ++covered;
    differ += a.owner[i] != b.owner[i] ? 1 : 0;
  }
  return covered == 0 ? 0.0 : double(differ) / double(covered);
}

// The eye-distance step of one depth step at distance d (the prediction's formula).
double depth_step(DepthFormat format, Mapping mapping, double d, double f, double ratio) {
  const double n = f / ratio;
  const double dz_dd = f * n / (d * d * (f - n));  // |dz_ndc / dd|, either mapping
  if (format != DepthFormat::D32Sfloat) return 1.0 / (std::pow(2.0, depth_bits(format)) - 1.0) / dz_dd;
  const double z = mapping == Mapping::Standard ? f * (d - n) / (d * (f - n)) : n * (f - d) / (d * (f - n));
  const float zf = float(z);
  const double ulp = double(std::nextafter(zf, 2.0f)) - double(zf);
  return ulp / dz_dd;
}

struct Series {
  DepthFormat format;
  Mapping mapping;
  std::vector<double> ratios, fractions;  // mean over the jitters
};

// The first ratio whose fraction passes kOnsetFraction and the one before it (0 when the first
// already does; infinity when none does).
std::pair<double, double> onset_bracket(const Series& s) {
  for (size_t i = 0; i < s.ratios.size(); ++i)
    if (s.fractions[i] > kOnsetFraction) return {i == 0 ? 0.0 : s.ratios[i - 1], s.ratios[i]};
  return {s.ratios.empty() ? 0.0 : s.ratios.back(), std::numeric_limits<double>::infinity()};
}

// The ratio where depth_step first reaches `gap` (bisection in log ratio); infinity past 1e12.
double predicted_onset(DepthFormat format, Mapping mapping, double d, double f, double gap) {
  double lo = 1.0 + 1e-9, hi = 1e12;
  if (depth_step(format, mapping, d, f, hi) < gap) return std::numeric_limits<double>::infinity();
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (depth_step(format, mapping, d, f, mid) >= gap ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace

void run_model_zfight_sweep(const ModelZfightOptions& o) {
  prepare_out_dir(o.sweep.out_dir);
  ImportOptions import;
  import.width = o.width;
  import.height = o.height;
  const std::string text = import_model_json(o.model, import);
  const Scene base = parse_scene(text, o.model);
  const nlohmann::json camera = nlohmann::json::parse(text).at("camera");
  const double far_plane = camera.at("far").get<double>(), framing_near = camera.at("near").get<double>();
  const auto at = [&](const char* key) {
    const auto& v = camera.at(key);
    return glm::dvec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  };
  const double target_distance = glm::length(at("eye") - at("target"));

  CpuOptions cpu = exact_cpu_options();
  cpu.threads = 2;  // the fast path: byte-identical to the exact one (tests/test_fast_exact.cpp)
  const std::vector<std::pair<double, double>> jitters =
      o.sweep.quick ? std::vector<std::pair<double, double>>{kJitters[0], kJitters[1]} : kJitters;
  std::vector<RenderResult> references;
  for (const auto& jitter : jitters)
    references.push_back(render_cpu(
        variant(base, far_plane, far_plane / framing_near, Mapping::Reversed, DepthFormat::D32Sfloat, jitter), cpu));

  const std::string csv_path = (std::filesystem::path(o.sweep.out_dir) / "zfight.csv").string();
  CsvAppender csv(csv_path, {"format", "mapping", "far_near", "jitter", "fraction"}, 4, o.sweep.resume);
  const std::vector<double> ratios = far_near_ratios(o.sweep.quick);
  const std::vector<DepthFormat> formats = sweep_depth_formats();
  Progress progress("zfight", formats.size() * 2 * ratios.size() * jitters.size());
  for (const DepthFormat format : formats)
    for (const Mapping mapping : {Mapping::Standard, Mapping::Reversed})
      for (const double ratio : ratios)
        for (size_t j = 0; j < jitters.size(); ++j) {
          const std::vector<std::string> key = {to_string(format), mapping_name(mapping), num(ratio), std::to_string(j)};
          if (csv.has(key)) {
            progress.skipped();
            continue;
          }
          const RenderResult r = render_cpu(variant(base, far_plane, ratio, mapping, format, jitters[j]), cpu);
          std::vector<std::string> row = key;
          row.push_back(num(owner_difference(r, references[j])));
          csv.append(row);
          progress.finished();
        }

  progress.done();

  // Mean over the jitters, from the CSV read back (a resumed run charts every point).
  const CsvTable table = read_csv(csv_path);
  std::vector<Series> series;
  for (const DepthFormat format : formats)
    for (const Mapping mapping : {Mapping::Standard, Mapping::Reversed}) {
      Series s{format, mapping, {}, {}};
      for (const double ratio : ratios) {
        double sum = 0;
        size_t count = 0;
        for (const auto& row : table.rows)
          if (row[0] == to_string(format) && row[1] == mapping_name(mapping) && row[2] == num(ratio)) {
            sum += std::stod(row[4]);
            ++count;
          }
        if (count == 0) continue;
        s.ratios.push_back(ratio);
        s.fractions.push_back(sum / double(count));
      }
      series.push_back(std::move(s));
    }

  // Calibrate the gap from D16 standard's onset bracket (the step at both of its ends), predict the
  // other series' onsets as intervals, and mark the ratio where the bracket's geometric middle puts it.
  const Series& d16 = series.front();
  const auto [d16_lo, d16_hi] = onset_bracket(d16);
  const bool calibrated = std::isfinite(d16_hi) && d16_lo > 0;
  const auto step_d16 = [&](double ratio) {
    return depth_step(DepthFormat::D16Unorm, Mapping::Standard, target_distance, far_plane, ratio);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double gap_lo = calibrated ? step_d16(d16_lo) : nan, gap_hi = calibrated ? step_d16(d16_hi) : nan;
  const double gap = calibrated ? step_d16(std::sqrt(d16_lo * d16_hi)) : nan;
  nlohmann::ordered_json report = {{"model", o.model},
                                   {"width", o.width},
                                   {"height", o.height},
                                   {"far", far_plane},
                                   {"framing_near", framing_near},
                                   {"target_distance", target_distance},
                                   {"onset_fraction", kOnsetFraction},
                                   {"jitters", jitters.size()},
                                   {"calibrated_gap", std::isfinite(gap) ? nlohmann::json(gap) : nlohmann::json()},
                                   {"calibrated_gap_interval", calibrated ? nlohmann::json({gap_lo, gap_hi})
                                                                          : nlohmann::json()}};
  std::vector<DataBlock> blocks;
  std::string arrows;
  std::vector<std::vector<std::string>> rows = {
      {"series", "measured onset (far/near)", "predicted onset interval", "fraction at the largest far/near"}};
  for (size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    const std::string name = std::string(to_string(s.format)) + ", " + mapping_name(s.mapping);
    const auto [lo, hi] = onset_bracket(s);
    const auto predict = [&](double g) {
      return std::isfinite(g) ? predicted_onset(s.format, s.mapping, target_distance, far_plane, g) : nan;
    };
    const double predicted = predict(gap), predicted_lo = predict(gap_lo), predicted_hi = predict(gap_hi);
    // The measured bracket (lo, hi] and the predicted interval [predicted_lo, predicted_hi] overlap;
    // both "none in the range" also agree.
    const bool none_predicted = !std::isfinite(predicted_lo) || predicted_lo > s.ratios.back();
    const bool agrees = !std::isfinite(hi) ? none_predicted : (predicted_lo <= hi && predicted_hi >= lo);
    const auto value = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    report["series"].push_back({{"format", to_string(s.format)},
                                {"mapping", mapping_name(s.mapping)},
                                {"measured_onset_above", value(lo)},
                                {"measured_onset_at_most", value(hi)},
                                {"predicted_onset", value(predicted)},
                                {"predicted_onset_interval", {value(predicted_lo), value(predicted_hi)}},
                                {"calibration", i == 0},
                                {"agrees", calibrated ? nlohmann::json(agrees) : nlohmann::json()}});
    DataBlock block{name, {{"\"" + name + "\"", "x"}}};
    for (size_t k = 0; k < s.ratios.size(); ++k) block.rows.push_back({num(s.ratios[k]), num(s.fractions[k])});
    blocks.push_back(block);
    if (std::isfinite(predicted) && predicted < 1e9)
      arrows += fmt::format("set arrow from {},graph 0 to {},graph 1 nohead lt {} dt 3\n", num(predicted), num(predicted),
                            i + 1);
    rows.push_back({name, std::isfinite(hi) ? fmt::format("({:.3g}, {:.3g}]", lo, hi) : fmt::format("none up to {:.3g}", lo),
                    none_predicted ? "none in the range"
                                   : fmt::format("[{:.3g}, {:.3g}]{}", predicted_lo, predicted_hi,
                                                 i == 0 ? " (calibration)" : agrees ? "" : " (disagrees)"),
                    fmt::format("{:.4f}", s.fractions.empty() ? 0.0 : s.fractions.back())});
  }
  write_json_file(o.sweep.out_dir, "zfight.json", report.dump(2) + "\n");
  write_zfight_tables(o.sweep.out_dir, report.dump());
  const std::string body =
      "set logscale x 10\nset format x '10^{%L}'\nset key outside right top\nset grid\nset style data linespoints\n"
      "set title " +
      gp_quote("Owners that differ from the precise render, against far/near: " +
               std::filesystem::path(o.model).filename().string()) +
      "\nset xlabel 'far / near (far fixed; dotted: the predicted onset)'\n"
      "set ylabel 'fraction of covered pixels'\n" +
      arrows + "plot for [i=0:" + std::to_string(blocks.size() - 1) +
      "] DATA index i using 1:2 title columnheader(1) lt (i+1)\n";
  render_chart(o.sweep.out_dir, "zfight_far_near", blocks, body);
  write_index_html(
      o.sweep.out_dir, "Z-fighting on " + std::filesystem::path(o.model).filename().string(),
      {{"Owners against far/near",
        fmt::format("Far fixed at {:.6g} (the framing camera's), near = far / R; {} sub-pixel jitters per point, each "
                    "compared with D32 reversed at the framing near ({:.6g}). Onset: the first R whose mean fraction "
                    "passes {}. Predicted from D16 standard's onset (gap {:.4g} at distance {:.4g}).",
                    far_plane, jitters.size(), framing_near, kOnsetFraction, gap, target_distance),
        {"zfight_far_near"},
        rows}},
      {"zfight.csv", "zfight.json"});
}

}  // namespace rastercmp::experiments
