#include "experiments/failure_boundary.hpp"

#include <numbers>
#include <stdexcept>

#include "cpu_raster/classic/method_registry.hpp"
#include "experiments/method_map_scenes.hpp"
#include "experiments/method_maps.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {

double map_measure(const CsvTable& table, const std::vector<std::string>& row, const std::string& measure) {
  if (measure == "any_mismatch")
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
        double previous = NAN;
        for (const Row& row :
             select_rows(table, {{"experiment", experiment}, {"case", case_name}, {"method", method}})) {
          ++b.points;
          if (row[agree] == "not_supported") {
            ++b.refused;
            b.refused_values.push_back(to_double(row[param]));
            continue;
          }
          const double p = to_double(row[param]);
          if (map_measure(table, row, measure) > 0) {
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

int format_bits(const std::string& case_name) {  // D32 near 1 steps by 2^-24, as 24 bits
  return case_name == "d16_unorm" ? 16 : case_name == "x8_d24_unorm" || case_name == "d32_sfloat" ? 24 : 0;
}

}  // namespace

std::optional<BoundaryPrediction> predicted_boundary(const std::string& experiment, const std::string& case_name,
                                                     const std::string& method) {
  const double cos30 = std::cos(kOnsetAngleDeg * std::numbers::pi / 180);
  if (experiment == "depth_far_near" && (method == "exact" || method == "depth=no_fma" || method == "depth=bilinear")) {
    // d = f/(f-n) (1 - n/z): one step 1/(2^B - 1) spans n dz / z^2, with n = far / R, far 100, the
    // pair dz = 0.1 / cos 30 apart at z = 56: R = far dz (2^B - 1) / z^2.
    const int bits = format_bits(case_name);
    if (bits == 0) return std::nullopt;
    return BoundaryPrediction{100 * (0.1 / cos30) * (std::ldexp(1.0, bits) - 1) / (56.0 * 56.0),
                              "far/near where one depth step n dz / z^2 equals 2^-" + std::to_string(bits) +
                                  " (far 100, dz 0.1 / cos 30, z 56)"};
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

BracketCheck check_bracket(const FailureBoundary& b, double predicted) {
  BracketCheck out;
  if (std::isnan(b.boundary)) return out;
  if (std::isnan(b.last_clean)) {
    out.measured_low = out.measured_high = b.boundary;
    return out;
  }
  const bool ascending = b.last_clean < b.boundary;
  out.measured_low = ascending ? b.last_clean : b.boundary;
  out.measured_high = ascending ? b.boundary : b.last_clean;
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
