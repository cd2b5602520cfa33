#include "experiments/polygon_offset.hpp"

#include <cmath>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "experiments/csv_log.hpp"
#include "experiments/depth_r.hpp"
#include "experiments/doc_table_renderers.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/pixel_stats.hpp"
#include "experiments/progress.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {
namespace {

DepthBias bias(double constant, double slope, double clamp = 0) {
  DepthBias b;
  b.enable = constant != 0 || slope != 0;
  // Negative factors pull the decal towards the eye under compare op Less.
  b.constant_factor = float(-constant);
  b.slope_factor = float(-slope);
  b.clamp = float(clamp);
  return b;
}

std::vector<double> ratios(bool quick) {
  if (quick) return {10, 1e3, 1e6};
  std::vector<double> r;
  for (int k = 2; k <= 12; ++k) r.push_back(std::pow(10.0, k / 2.0));
  return r;
}

PairParams pair(PairKind kind, DepthFormat format, double ratio, double angle, DepthBias b) {
  PairParams p;
  p.kind = kind;
  p.format = format;
  p.far_near_ratio = ratio;
  p.angle_deg = angle;
  p.separation = kind == PairKind::NearCoplanar ? 0.05 : 0.0;
  p.decal_bias = b;
  return p;
}

void add_far_near(std::vector<OffsetSeries>& plan, bool quick) {
  const std::pair<double, double> offsets[] = {{0, 0}, {1, 1}, {4, 2}};
  for (PairKind kind : {PairKind::Coplanar, PairKind::NearCoplanar, PairKind::House})
    for (DepthFormat format : sweep_depth_formats())
      for (auto [c, s] : offsets) {
        OffsetSeries series;
        for (double ratio : ratios(quick)) series.push_back({"far_near", pair(kind, format, ratio, 45, bias(c, s))});
        plan.push_back(series);
      }
}

void add_factor_axes(std::vector<OffsetSeries>& plan, bool quick) {
  const std::vector<double> angles = quick ? std::vector<double>{0, 60} : std::vector<double>{0, 15, 30, 45, 60, 75};
  const std::vector<double> constants = quick
                                            ? std::vector<double>{0, 1, 16, 256}
                                            : std::vector<double>{0, 0.5, 1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024};
  const std::vector<double> slopes =
      quick ? std::vector<double>{0, 1, 4} : std::vector<double>{0, 0.25, 0.5, 1, 2, 4, 8};
  for (PairKind kind : {PairKind::Coplanar, PairKind::NearCoplanar})
    for (DepthFormat format : sweep_depth_formats())
      for (double angle : angles) {
        OffsetSeries by_constant, by_slope;
        for (double c : constants) by_constant.push_back({"constant", pair(kind, format, 1000, angle, bias(c, 0))});
        for (double s : slopes) by_slope.push_back({"slope", pair(kind, format, 1000, angle, bias(0, s))});
        plan.push_back(by_constant);
        plan.push_back(by_slope);
      }
}

void add_clamp_and_angle(std::vector<OffsetSeries>& plan, bool quick) {
  const std::vector<double> clamps =
      quick ? std::vector<double>{-1e-6, -1e-3, 0} : std::vector<double>{-1e-7, -1e-6, -1e-5, -1e-4, -1e-3, -1e-2, 0};
  for (DepthFormat format : sweep_depth_formats()) {
    OffsetSeries series;
    for (double clamp : clamps)
      series.push_back({"clamp", pair(PairKind::Coplanar, format, 1000, 60, bias(256, 4, clamp))});
    plan.push_back(series);
  }
  std::vector<double> angles;
  for (int a = 0; a <= 80; a += quick ? 40 : 10) angles.push_back(a);
  for (PairKind kind : {PairKind::Coplanar, PairKind::NearCoplanar})
    for (DepthFormat format : sweep_depth_formats())
      for (auto [c, s] : {std::pair<double, double>{0, 0}, {1, 1}}) {
        OffsetSeries series;
        for (double angle : angles) series.push_back({"angle", pair(kind, format, 1000, angle, bias(c, s))});
        plan.push_back(series);
      }
}

// The control: one triangle drawn twice with the same vertices, the second with constant offset 0
// and 1 (units of r), per format and viewing angle.
void add_identical(std::vector<OffsetSeries>& plan, bool quick) {
  const std::vector<double> angles = quick ? std::vector<double>{0, 60} : std::vector<double>{0, 30, 60, 75};
  for (DepthFormat format : sweep_depth_formats())
    for (double angle : angles) {
      OffsetSeries series;
      for (double constant : {0.0, 1.0})
        series.push_back({"identical", pair(PairKind::Identical, format, 1000, angle, bias(constant, 0))});
      plan.push_back(series);
    }
}

std::vector<std::string> key_of(const OffsetPoint& point) {
  const PairParams& p = point.params;
  return {point.experiment,
          to_string(p.kind),
          to_string(p.format),
          num(p.far_near_ratio),
          num(p.angle_deg),
          num(-p.decal_bias.constant_factor),
          num(-p.decal_bias.slope_factor),
          num(p.decal_bias.clamp),
          num(p.separation)};
}

bool series_done(const CsvAppender& csv, const OffsetSeries& series) {
  for (const OffsetPoint& point : series)
    if (!csv.has(key_of(point))) return false;
  return true;
}

// Renders a whole series (flips need the neighbour) and appends the rows the CSV lacks.
void run_series(VulkanRenderer& vk, CsvAppender& csv, const OffsetSeries& series, Progress& progress) {
  std::optional<BackendPair> previous;
  for (const OffsetPoint& point : series) {
    const DecalScene decal = make_decal_scene(point.params);
    const std::vector<bool> mask = covered_mask(render_cpu(decal_only(decal), exact_cpu_options()));
    BackendPair now = render_both(vk, decal.scene);
    const double nan = std::nan("");
    const double flip_cpu = previous ? owner_change_fraction(previous->cpu, now.cpu, mask) : nan;
    const double flip_vk = previous ? owner_change_fraction(previous->vk, now.vk, mask) : nan;
    std::vector<std::string> row = key_of(point);
    row.insert(row.end(), {num(wrong_surface_fraction(now.cpu, mask, decal.decal_draw)),
                           num(wrong_surface_fraction(now.vk, mask, decal.decal_draw)), num(flip_cpu), num(flip_vk),
                           flag(compare_results(now.cpu, now.vk).identical()), num(double(count(mask)))});
    if (!csv.has(row)) csv.append(row);
    previous = std::move(now);
    progress.finished();
  }
}

}  // namespace

std::string r_json(const std::vector<DepthRMeasure>& measures) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const DepthRMeasure& m : measures)
    out.push_back({{"format", to_string(m.format)},
                   {"r_cpu", m.r_cpu},
                   {"r_vulkan", m.r_vk},
                   {"raw_step_cpu", m.raw_step_cpu},
                   {"raw_step_vulkan", m.raw_step_vk},
                   {"spec_bound", m.spec_bound},
                   {"lavapipe_formula", m.lavapipe_formula},
                   {"r_over_spec_bound", m.r_vk / m.spec_bound},
                   {"predicted", m.lavapipe_formula},
                   {"predicted_over_spec_bound", m.lavapipe_formula / m.spec_bound},
                   {"measured_over_predicted", m.r_vk / m.lavapipe_formula}});
  return out.dump(2) + "\n";
}

std::vector<IdenticalControl> identical_controls(const CsvTable& table) {
  std::vector<IdenticalControl> out;
  const size_t format = table.column("format"), angle = table.column("angle_deg"), constant = table.column("constant"),
               cpu = table.column("wrong_cpu"), vk = table.column("wrong_vk"), agree = table.column("cpu_vk_agree");
  for (const Row& row : select_rows(table, {{"experiment", "identical"}})) {
    IdenticalControl c{row[format], to_double(row[angle]), to_double(row[constant]), to_double(row[cpu]),
                       to_double(row[vk]), row[agree] == "true", false};
    // Without offset the second draw ties the first everywhere and loses under Less; with 1 r it
    // must win every pixel (the spec: r is the smallest difference that separates two depths).
    c.as_expected = c.constant == 0 ? (c.wrong_cpu == 1 && c.wrong_vk == 1) : (c.wrong_cpu == 0 && c.wrong_vk == 0);
    out.push_back(c);
  }
  return out;
}

std::string identical_control_json(const CsvTable& table) {
  nlohmann::ordered_json controls = nlohmann::ordered_json::array();
  for (const IdenticalControl& c : identical_controls(table))
    controls.push_back({{"format", c.format},
                        {"angle_deg", c.angle_deg},
                        {"constant", c.constant},
                        {"wrong_cpu", c.wrong_cpu},
                        {"wrong_vulkan", c.wrong_vk},
                        {"cpu_vk_agree", c.cpu_vk_agree},
                        {"expected", c.constant == 0 ? "the second draw loses every pixel (equal depth, Less)"
                                                     : "the second draw wins every pixel (1 r separates)"},
                        {"as_expected", c.as_expected}});
  nlohmann::ordered_json out{{"identical_vertex_control", controls}};
  return out.dump(2) + "\n";
}

std::vector<std::string> polygon_offset_header() {
  return {"experiment", "scene",     "format",   "far_near", "angle_deg", "constant",     "slope",      "clamp",
          "separation", "wrong_cpu", "wrong_vk", "flip_cpu", "flip_vk",   "cpu_vk_agree", "mask_pixels"};
}

std::vector<OffsetSeries> polygon_offset_plan(bool quick) {
  std::vector<OffsetSeries> plan;
  add_far_near(plan, quick);
  add_factor_axes(plan, quick);
  add_clamp_and_angle(plan, quick);
  add_identical(plan, quick);
  return plan;
}

void run_polygon_offset_sweep(const SweepOptions& options) {
  find_gnuplot();  // fail before the long part
  prepare_out_dir(options.out_dir);
  VulkanRenderer vk(VkOptions{});
  const std::vector<OffsetSeries> plan = polygon_offset_plan(options.quick);
  size_t total = 0;
  for (const OffsetSeries& series : plan) total += series.size();
  CsvAppender csv((std::filesystem::path(options.out_dir) / kPolygonOffsetCsv).string(), polygon_offset_header(), 9,
                  options.resume);
  Progress progress("sweep polygon-offset", total);
  for (const OffsetSeries& series : plan) {
    if (series_done(csv, series)) {
      for (size_t i = 0; i < series.size(); ++i) progress.skipped();
      continue;
    }
    run_series(vk, csv, series, progress);
  }
  progress.done();
  const std::vector<DepthRMeasure> r = measure_depth_r(vk);
  const std::string depth_r = r_json(r);
  write_json_file(options.out_dir, "depth_r.json", depth_r);
  write_depth_r_tables(options.out_dir, depth_r);
  const std::string controls =
      identical_control_json(read_csv((std::filesystem::path(options.out_dir) / kPolygonOffsetCsv).string()));
  write_json_file(options.out_dir, "polygon_offset.json", controls);
  write_polygon_offset_tables(options.out_dir, controls);
  write_polygon_offset_charts(options.out_dir, r);
}

}  // namespace rastercmp::experiments
