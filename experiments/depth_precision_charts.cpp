// The outputs of `rastercmp chart depth-precision`: depth_precision.csv, depth_precision.json, one
// chart per format (Δz against w above, measured / ideal below) and index.html.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "experiments/doc_table_renderers.hpp"
#include "experiments/depth_precision.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/html_page.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"

namespace rastercmp::experiments {
namespace {

// Measured against the ideal bucket: "agrees" within this factor either way.
constexpr double kAgreeFactor = 1.1;

struct SeriesSummary {
  DepthFormat format;
  PrecisionMapping mapping;
  size_t points = 0, open = 0, agree = 0;
  double min_ratio = NAN, median_ratio = NAN, max_ratio = NAN;
  double first_departure_w = NAN;  // the smallest w whose measured / ideal leaves [1/1.1, 1.1]
  bool renders_agree = true;
};

std::vector<SeriesSummary> summarise(const std::vector<PrecisionPoint>& points) {
  std::vector<SeriesSummary> out;
  for (DepthFormat format : sweep_depth_formats())
    for (PrecisionMapping mapping : kPrecisionMappings) {
      SeriesSummary s{format, mapping};
      std::vector<double> ratios;
      for (const PrecisionPoint& p : points) {
        if (p.format != format || p.mapping != mapping) continue;
        ++s.points;
        s.renders_agree = s.renders_agree && p.render_agrees;
        if (p.bucket.open) {
          ++s.open;
          continue;
        }
        const double ratio = p.measured / p.ideal;
        ratios.push_back(ratio);
        if (ratio <= kAgreeFactor && ratio >= 1 / kAgreeFactor)
          ++s.agree;
        else if (std::isnan(s.first_departure_w))
          s.first_departure_w = p.w;
      }
      if (!ratios.empty()) {
        std::sort(ratios.begin(), ratios.end());
        s.min_ratio = ratios.front();
        s.max_ratio = ratios.back();
        s.median_ratio = ratios[ratios.size() / 2];
      }
      out.push_back(s);
    }
  return out;
}

nlohmann::ordered_json number(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); }

std::string format_label(DepthFormat format) {
  std::string name = to_string(format);
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return name;
}

void chart_format(const std::string& dir, DepthFormat format, const std::vector<PrecisionPoint>& points,
                  const DepthPlanes& planes) {
  std::vector<DataBlock> blocks;
  for (PrecisionMapping mapping : kPrecisionMappings) {
    DataBlock block{to_string(mapping), {}};
    for (const PrecisionPoint& p : points)
      if (p.format == format && p.mapping == mapping)
        block.rows.push_back({num(p.w), p.bucket.open ? "NaN" : num(p.measured), p.bucket.open ? "NaN" : num(p.analytic),
                              p.bucket.open ? "NaN" : num(p.measured / p.ideal), num(p.w_spacing)});
    blocks.push_back(block);
  }
  std::string upper, lower;
  for (size_t i = 0; i < blocks.size(); ++i) {
    const std::string name = blocks[i].title;
    upper += fmt::format("{}DATA index {} using 1:2 with points lt {} title {}, "
                         "DATA index {} using 1:3 with lines lt {} dt 1 title {}",
                         i ? ", \\\n  " : "", i, i + 1, gp_quote(name + " measured"), i, i + 1,
                         gp_quote(name + " analytic"));
    lower += fmt::format("{}DATA index {} using 1:4 with linespoints lt {} title {}", i ? ", \\\n  " : "",
                         i, i + 1, gp_quote(name));
  }
  upper += ", \\\n  DATA index 0 using 1:5 with lines lc rgb '#888888' dt 2 lw 1.5 title 'float spacing of w'";
  const std::string body = fmt::format(
      "set multiplot title {} noenhanced\n"
      "set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\nset grid\n"
      "set lmargin 12\nset rmargin 30\n"
      "set key outside right top font ',10'\n"
      "set size 1,0.62\nset origin 0,0.36\n"
      "set xlabel 'eye distance w'\nset ylabel 'Δz (step in w that changes the stored depth)'\n"
      "plot {}\n"
      "set size 1,0.36\nset origin 0,0\nset tmargin 1\n"
      "set format y '%g'\nset yrange [*:*]\n"
      "set ylabel 'measured / ideal bucket'\n"
      "set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2 lc rgb '#888888'\n"
      "plot {}\n"
      "unset multiplot\n",
      gp_quote(fmt::format("Depth precision, {}: near {:g}, far {:g} (points: exact path; lines: analytic)",
                           format_label(format), planes.near_plane, planes.far_plane)),
      upper, lower);
  render_chart(dir, std::string("depth_precision_") + to_string(format), blocks, body);
}

std::string json_text(const std::vector<PrecisionPoint>& points, const std::vector<SeriesSummary>& series,
                      const DepthPlanes& planes, int per_decade) {
  nlohmann::ordered_json out;
  out["near"] = planes.near_plane;
  out["far"] = planes.far_plane;
  out["points_per_decade"] = per_decade;
  out["fma"] = exact_cpu_options().fma;
  out["analytic"] = {{"finite", "q(z) w^2 (f - n) / (f n)"},
                     {"infinite", "q(z) w^2 / n"},
                     {"q_unorm", "1 / (2^B - 1)"},
                     {"q_float", "2^(floor(log2 z) - 23)"}};
  out["agree_factor"] = kAgreeFactor;
  out["series"] = nlohmann::ordered_json::array();
  for (const SeriesSummary& s : series)
    out["series"].push_back({{"format", to_string(s.format)},
                             {"mapping", to_string(s.mapping)},
                             {"points", s.points},
                             {"open_buckets", s.open},
                             {"agree", s.agree},
                             {"measured_over_ideal_min", number(s.min_ratio)},
                             {"measured_over_ideal_median", number(s.median_ratio)},
                             {"measured_over_ideal_max", number(s.max_ratio)},
                             {"first_departure_w", number(s.first_departure_w)},
                             {"render_check_agrees", s.renders_agree}});
  out["points"] = nlohmann::ordered_json::array();
  for (const PrecisionPoint& p : points)
    out["points"].push_back({{"format", to_string(p.format)},
                             {"mapping", to_string(p.mapping)},
                             {"w", p.w},
                             {"raw", p.bucket.raw},
                             {"w_low", p.bucket.w_low},
                             {"w_high", p.bucket.w_high},
                             {"open", p.bucket.open},
                             {"measured", p.measured},
                             {"analytic", p.analytic},
                             {"ideal", p.ideal},
                             {"w_float_spacing", p.w_spacing},
                             {"render_check_agrees", p.render_agrees}});
  return out.dump(2) + "\n";
}

std::string ratio_text(double v) { return std::isfinite(v) ? fmt::format("{:.3g}", v) : "—"; }

}  // namespace

void run_depth_precision(const SweepOptions& options, const DepthPlanes& planes) {
  if (!(planes.near_plane > 0) || !(planes.far_plane > planes.near_plane) || !std::isfinite(planes.far_plane))
    throw UsageError(fmt::format("depth-precision: expected 0 < --near < --far, both finite, found near {} far {}",
                                 planes.near_plane, planes.far_plane));
  find_gnuplot();
  prepare_out_dir(options.out_dir);
  const int per_decade = options.quick ? 4 : 10;
  const std::vector<PrecisionPoint> points = measure_depth_precision(planes, per_decade, true);
  const std::vector<SeriesSummary> series = summarise(points);
  {
    std::string csv =
        "format,mapping,w,raw,w_low,w_high,open,measured,analytic,ideal,measured_over_ideal,w_float_spacing,"
        "render_check_agrees\n";
    for (const PrecisionPoint& p : points)
      csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", to_string(p.format), to_string(p.mapping),
                         num(p.w), p.bucket.raw, num(p.bucket.w_low), num(p.bucket.w_high), flag(p.bucket.open),
                         num(p.measured), num(p.analytic), num(p.ideal), num(p.measured / p.ideal),
                         num(p.w_spacing), flag(p.render_agrees));
    write_text_file_atomic((std::filesystem::path(options.out_dir) / "depth_precision.csv").string(), csv);
  }
  const std::string json = json_text(points, series, planes, per_decade);
  write_json_file(options.out_dir, "depth_precision.json", json);
  write_depth_precision_tables(options.out_dir, json);
  std::vector<PageSection> sections{
      {"Method",
       fmt::format("A surface facing the eye at eye distance w stores one raw depth value. Δz(w) is the width of the "
                   "set of float eye distances that store the same value (bisection over the float bits of w on the "
                   "exact path's stored value: clip z as the mapping forms it, window_from_clip_jit, sample_depth). "
                   "Every bucket's edges and their outer neighbours are also rendered with render_cpu; it stores the "
                   "same values on {} of {} points. Analytic (lines): q(z) w^2 (f - n)/(f n) for the finite mappings, "
                   "q(z) w^2/n for the infinite ones, q = 1/(2^B - 1) (UNORM) or the float spacing at z (D32). "
                   "The lower panels divide the measured width by the ideal bucket (the same rounding in exact "
                   "arithmetic); a bucket that reaches a clamped end (w at near or far) is open and not drawn.",
                   std::count_if(points.begin(), points.end(), [](const PrecisionPoint& p) { return p.render_agrees; }),
                   points.size()),
       {}}};
  for (DepthFormat format : sweep_depth_formats()) {
    chart_format(options.out_dir, format, points, planes);
    std::vector<std::vector<std::string>> table{{"mapping", "points (open)", "within 10% of ideal",
                                                 "measured / ideal: min", "median", "max", "first w outside 10%"}};
    for (const SeriesSummary& s : series)
      if (s.format == format)
        table.push_back({to_string(s.mapping), fmt::format("{} ({})", s.points, s.open), std::to_string(s.agree),
                         ratio_text(s.min_ratio), ratio_text(s.median_ratio), ratio_text(s.max_ratio),
                         ratio_text(s.first_departure_w)});
    sections.push_back({format_label(format), "", {std::string("depth_precision_") + to_string(format)}, table});
  }
  write_index_html(options.out_dir, "Depth precision against eye distance", sections,
                   {"depth_precision.csv", "depth_precision.json"});
}

}  // namespace rastercmp::experiments
