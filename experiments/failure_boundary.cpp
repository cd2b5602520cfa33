#include "experiments/failure_boundary.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>

#include <fmt/core.h>

#include "cpu_raster/classic/method_registry.hpp"
#include "experiments/method_map_scenes.hpp"
#include "experiments/map_theory.hpp"
#include "experiments/method_maps.hpp"
#include "experiments/pixel_stats.hpp"
#include "experiments/scene_make.hpp"
#include "experiments/stability.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {

double map_measure(const CsvTable& table, const std::vector<std::string>& row, const std::string& measure) {
  if (measure == "any_mismatch" || measure == "excess_mismatch")
    return to_double(row[table.column("coverage_mismatch")]) + to_double(row[table.column("depth_mismatch")]);
  return to_double(row[table.column(measure)]);
}

std::vector<FailureBoundary> failure_boundaries(const CsvTable& table) {
  std::vector<FailureBoundary> out;
  const size_t param = table.column("param_a"), agree = table.column("cpu_vk_agree");
  for (const MapExperiment& e : method_map_experiments()) {
    const std::string experiment(e.name);
    const std::string measure(e.measure);
    for (const std::string& case_name : distinct(table, "case", {{"experiment", experiment}}))
      for (const std::string& method : distinct(table, "method", {{"experiment", experiment}, {"case", case_name}})) {
        FailureBoundary b{experiment, std::string(e.family), case_name, method, NAN, NAN, 0, 0, 0, {}};
        double previous = NAN, threshold = measure == "excess_mismatch" ? NAN : 0;
        for (const Row& row :
             select_rows(table, {{"experiment", experiment}, {"case", case_name}, {"method", method}})) {
          ++b.points;
          if (row[agree] == "not_supported") {
            ++b.refused;
            b.refused_values.push_back(to_double(row[param]));
            continue;
          }
          const double p = to_double(row[param]), value = map_measure(table, row, measure);
          if (std::isnan(threshold)) threshold = value;  // excess_mismatch: the benign end's own mismatch
          if (value > threshold) {
            ++b.failing;
            if (std::isnan(b.boundary)) {
              b.boundary = p;
              b.last_clean = previous;
            }
          }
          previous = p;
        }
        out.push_back(b);
      }
  }
  return out;
}

namespace {

int format_bits(const std::string& format) {  // D32 near 1 steps by 2^-24, as 24 bits
  return format == "d16_unorm" ? 16 : format == "x8_d24_unorm" || format == "d32_sfloat" ? 24 : 0;
}

}  // namespace

std::optional<OnsetPrediction> predicted_onset(const std::string& case_name, double separation) {
  const std::string format = case_depth_format(case_name);
  const DepthMapping mapping = case_depth_mapping(case_name);
  const int bits = format_bits(format);
  if (bits == 0) return std::nullopt;
  // Reversed D32 stores z ~ n / w, where a float's step is relative (z 2^-24): the pair fights once
  // dz / w < 2^-24, never for these separations, whatever far/near.
  if (format == "d32_sfloat" && is_reversed(mapping)) return std::nullopt;
  // d = f/(f-n) (1 - n/w) (reversed: its mirror): one step 1/(2^B - 1) spans n dz / w^2, with
  // n = far / R, far 100, the pair dz = s / cos 30 apart at w = 56: R = far dz (2^B - 1) / w^2.
  const double cos30 = std::cos(kOnsetAngleDeg * std::numbers::pi / 180);
  const double one_step = 100 * (separation / cos30) * (std::ldexp(1.0, bits) - 1) / (56.0 * 56.0);
  return OnsetPrediction{one_step, "far/near where one depth step n dz / w^2 equals 2^-" + std::to_string(bits) +
                                       " (far 100, dz = separation / cos 30, w 56)"};
}

std::optional<BoundaryPrediction> predicted_boundary(const std::string& experiment, const std::string& case_name,
                                                     const std::string& method) {
  if (auto line_or_cull = method_map_prediction(experiment, case_name, method)) return line_or_cull;
  const double cos30 = std::cos(kOnsetAngleDeg * std::numbers::pi / 180);
  const bool interpolates_the_plane = method == "exact" || method == "depth=no_fma" || method == "depth=bilinear";
  if (experiment == "depth_far_near" && interpolates_the_plane) {
    if (const auto onset = predicted_onset(case_name, 0.1)) return BoundaryPrediction{onset->value, onset->formula};
    return std::nullopt;
  }
  if (experiment == "coplanar_offset" && (interpolates_the_plane || method == "depth=perspective_correct")) {
    // The decal wins a pixel once its biased depth is stored at least one step below the base's:
    // offset c r >= (D + 1) steps, D the discrepancy at zero offset. lavapipe's UNORM r is 2 steps
    // (lavapipe-rules §4.3): c = (D + 1) / 2; D32's r = 2^(e-23) = one float step of [0.5, 1): c = D + 1.
    const DepthFormat format = case_name == "d16_unorm"      ? DepthFormat::D16Unorm
                               : case_name == "x8_d24_unorm" ? DepthFormat::X8D24Unorm
                               : case_name == "d32_sfloat"   ? DepthFormat::D32Sfloat
                                                             : DepthFormat::None;
    if (format == DepthFormat::None) return std::nullopt;
    const double d = coplanar_discrepancy_steps(format, method);
    const bool unorm = format != DepthFormat::D32Sfloat;
    return BoundaryPrediction{unorm ? (d + 1) / 2 : d + 1,
                              fmt::format("smallest offset: (D + 1) {} with D = {:g} raw steps, the decal's largest "
                                          "excess over the base at zero offset",
                                          unorm ? "/ 2 (r = 2 steps)" : "(r = 1 float step)", d),
                              true};
  }
  if (experiment == "pseudo_depth" && method.rfind("depth=pseudo_depth_", 0) == 0) {
    // One step of (1 - pz) / 2 spans pseudo_depth_step_at_far(far, B) (w / far)^2 in w; the pair is
    // s / cos 30 apart in w; its far corner is at w = 0.8 far 1.12.
    const int bits = format_bits(case_name);
    const double far_distance = cpu::classic::pseudo_depth_far(method.substr(6));
    if (bits == 0 || far_distance == 0) return std::nullopt;
    const double w = 0.8 * far_distance * 1.12;
    return BoundaryPrediction{cpu::classic::pseudo_depth_step_at_far(far_distance, bits) * (w / far_distance) *
                                  (w / far_distance) * cos30,
                              "separation whose w gap s / cos 30 equals one " + std::to_string(bits) +
                                  "-bit pseudo-depth step at the far corner (w = 0.896 far)"};
  }
  if (experiment == "visibility_cyclic" && method == "visibility=painter") {
    const double a = 8 * std::sqrt(3.0) / 28;
    return BoundaryPrediction{0.05 / (a + 3 / std::sin(std::numbers::pi / 3) / 28),
                              "first contact of the 6 px wide bars: 0.05 / (a + 3 / sin 60 / 28), a = 8 tan 60 / 28"};
  }
  if (experiment == "visibility_interpenetration" && method == "visibility=painter")
    return BoundaryPrediction{kInterpenetrationOnset + 0.2 * 0.5 / 32,
                              "penetration at which the first pixel centre (x 16.5) of the tilted square is in front"};
  return std::nullopt;
}

double coplanar_discrepancy_steps(DepthFormat format, const std::string& method) {
  PairParams p;
  p.kind = PairKind::Coplanar;
  p.format = format;
  p.far_near_ratio = 1000;
  p.angle_deg = kOnsetAngleDeg;
  const DecalScene pair = make_decal_scene(p);
  CpuOptions cpu = exact_cpu_options();
  for (const NamedMethod& m : family_methods("depth"))
    if (m.first == method) cpu = m.second;
  Scene base = pair.scene, decal = pair.scene;  // each drawn alone with its depth test and write
  base.draws = {pair.scene.draws[0]};
  decal.draws = {pair.scene.draws[pair.decal_draw]};
  const RenderResult base_alone = render_cpu(base, cpu), decal_alone = render_cpu(decal, cpu);
  const std::vector<bool> mask = covered_mask(render_cpu(decal_only(pair), cpu));
  double worst = -INFINITY;
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i])  // UNORM integers and positive float bits both order as the depths they stand for
      worst = std::max(worst, double(decal_alone.depth_raw[i]) - double(base_alone.depth_raw[i]));
  return std::isfinite(worst) ? worst : NAN;
}

BracketCheck check_bracket(const FailureBoundary& b, double predicted, bool clean_at_value) {
  BracketCheck out;
  if (std::isnan(b.boundary)) return out;
  if (std::isnan(b.last_clean)) {
    out.measured_low = out.measured_high = b.boundary;
    return out;
  }
  const bool ascending = b.last_clean < b.boundary;
  out.measured_low = ascending ? b.last_clean : b.boundary;
  out.measured_high = ascending ? b.boundary : b.last_clean;
  if (clean_at_value)  // the boundary lies between the failing value and the clean one, this end included
    out.in_bracket = ascending ? (predicted >= b.last_clean && predicted < b.boundary)
                               : (predicted <= b.last_clean && predicted > b.boundary);
  else
    out.in_bracket = ascending ? (predicted > b.last_clean && predicted <= b.boundary)
                               : (predicted < b.last_clean && predicted >= b.boundary);
  return out;
}

const FailureBoundary& find_boundary(const std::vector<FailureBoundary>& all, const std::string& experiment,
                                     const std::string& case_name, const std::string& method) {
  for (const FailureBoundary& b : all)
    if (b.experiment == experiment && b.case_name == case_name && b.method == method) return b;
  throw std::out_of_range("no series " + experiment + " / " + case_name + " / " + method);
}

}  // namespace rastercmp::experiments
