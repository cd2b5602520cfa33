#include "experiments/stability.hpp"

#include <cmath>
#include <filesystem>
#include <limits>

#include "experiments/csv_log.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/method_maps.hpp"
#include "experiments/pixel_stats.hpp"
#include "experiments/progress.hpp"
#include "experiments/scene_make.hpp"
#include "model/errors.hpp"

namespace rastercmp::experiments {
namespace {

std::vector<double> pick(bool quick, std::vector<double> small, std::vector<double> full) {
  return quick ? small : full;
}

// Every (format, mapping, separation, far/near) at kOnsetJitters(quick) jitters: sub-pixel offset
// and depth phase (ensemble_jitter), so an onset is a distribution, not one placement's.
void add_fight_onset(std::vector<StabilityPoint>& plan, bool quick) {
  std::vector<double> ratios;
  for (int k = 4; k <= 24; k += quick ? 4 : 1) ratios.push_back(std::pow(10.0, k / 4.0));
  for (DepthMapping mapping : kDepthMappings)
    for (DepthFormat format : sweep_depth_formats())
      for (double separation : pick(quick, {0.1}, {0.01, 0.1, 1}))
        for (int j = 0; j < onset_jitters(quick); ++j)
          for (double ratio : ratios) {
            const Jitter jitter = ensemble_jitter(j);
            PairParams p;
            p.kind = PairKind::NearCoplanar;
            p.format = format;
            p.far_near_ratio = ratio;
            p.angle_deg = kOnsetAngleDeg;
            p.separation = separation;
            p.jitter_x_px = jitter.x_px;
            p.jitter_y_px = jitter.y_px;
            p.distance += jitter.depth_phase * kOnsetDepthPhaseRange;
            StabilityPoint point{"fight_onset", std::string(to_string(format)) + mapping_suffix(mapping), "exact",
                                 separation, ratio,
                                 [p, mapping] {
                                   return with_depth_mapping(make_decal_scene(p).scene, mapping,
                                                             p.far_plane / p.far_near_ratio, p.far_plane);
                                 },
                                 exact_cpu_options(), 1, true};
            point.jitter = j;
            plan.push_back(point);
          }
}

void add_slivers(std::vector<StabilityPoint>& plan, bool quick) {
  for (const auto& [name, cpu] : fill_methods())
    for (double angle : pick(quick, {0.1, 3}, {0.01, 0.03, 0.1, 0.3, 1, 3, 10}))
      for (double length : pick(quick, {8, 60}, {4, 8, 16, 32, 60}))
        plan.push_back({"sliver", "sliver_pair", name, angle, length,
                        [angle, length] { return make_sliver_pair(angle, length); }, cpu, 0});
}

void add_limits(std::vector<StabilityPoint>& plan, bool quick) {
  for (double distance : pick(quick, {64, 4096, 32767}, {64, 256, 1024, 4096, 8192, 16384, 24576, 32767}))
    plan.push_back({"far_distance", "far_triangle", "exact", distance, 0,
                    [distance] { return make_far_triangle(distance); }, exact_cpu_options(), 0});
  for (double w :
       pick(quick, {1, 1e-3, 1e-20, 0, -1e-6}, {1, 1e-1, 1e-2, 1e-3, 1e-5, 1e-8, 1e-12, 1e-20, 1e-30, 1e-38, 0, -1e-6}))
    plan.push_back(
        {"near_w", "near_w", "exact", w, 0, [w] { return make_near_w_triangle(float(w)); }, exact_cpu_options(), 0});
  const char* components[] = {"x", "y", "z", "w"};
  const float inf = std::numeric_limits<float>::infinity();
  for (uint32_t c = 0; c < 4; ++c)
    for (float value : {std::numeric_limits<float>::quiet_NaN(), inf, -inf})
      plan.push_back({"non_finite", components[c], "exact", double(value), 0,
                      [c, value] { return make_non_finite_triangle(c, value); }, exact_cpu_options(), 0});
}

std::vector<std::string> key_of(const StabilityPoint& p) {
  return {p.experiment, p.case_name, p.method, num(p.param_a), num(p.param_b), std::to_string(p.jitter)};
}

}  // namespace

// value_* columns: wrong-surface fraction, or covered pixels.
std::vector<std::string> measure_stability_point(const StabilityPoint& point, const ReferenceRender& reference) {
  const Scene scene = point.make_scene();
  const RenderResult gpu = reference(scene);
  std::vector<std::string> row = key_of(point);
  RenderResult cpu;
  try {
    cpu = render_cpu(scene, point.cpu);
  } catch (const NotSupportedError&) {
    row.insert(row.end(), {"nan", num(double(count(covered_mask(gpu)))), "nan", "nan", "not_supported"});
    return row;
  }
  const Mismatch m = compare_results(cpu, gpu);
  if (point.wrong_surface) {
    const std::vector<bool> mask = covered_mask(render_cpu(decal_only({scene, point.decal_draw}), point.cpu));
    row.insert(row.end(), {num(wrong_surface_fraction(cpu, mask, point.decal_draw)),
                           num(wrong_surface_fraction(gpu, mask, point.decal_draw))});
  } else {
    row.insert(row.end(), {num(double(count(covered_mask(cpu)))), num(double(count(covered_mask(gpu))))});
  }
  row.insert(row.end(), {num(double(m.coverage)), num(double(m.depth)), flag(m.identical())});
  return row;
}

std::vector<std::string> stability_header() {
  return {"experiment", "case",     "method",            "param_a",        "param_b",     "jitter",
          "value_cpu",  "value_vk", "coverage_mismatch", "depth_mismatch", "cpu_vk_agree"};
}

std::vector<StabilityPoint> stability_plan(bool quick) {
  std::vector<StabilityPoint> plan;
  add_fight_onset(plan, quick);
  add_slivers(plan, quick);
  add_limits(plan, quick);
  add_method_maps(plan, quick);
  return plan;
}

void run_stability_sweep(const SweepOptions& options) {
  find_gnuplot();
  prepare_out_dir(options.out_dir);
  VulkanRenderer vk(VkOptions{});
  const std::vector<StabilityPoint> plan = stability_plan(options.quick);
  CsvAppender csv((std::filesystem::path(options.out_dir) / kStabilityCsv).string(), stability_header(), 6,
                  options.resume);
  Progress progress("sweep stability", plan.size());
  for (const StabilityPoint& point : plan) {
    if (csv.has(key_of(point))) {
      progress.skipped();
      continue;
    }
    csv.append(measure_stability_point(point, [&vk](const Scene& scene) { return vk.render(scene); }));
    progress.finished();
  }
  progress.done();
  write_stability_outputs(options.out_dir);
}

}  // namespace rastercmp::experiments
