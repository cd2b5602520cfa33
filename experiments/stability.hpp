// `rastercmp sweep stability`: where methods stop being right. Experiments (column "experiment"):
//   fight_onset   near-coplanar pair per depth format, clip-z mapping and separation against far/near,
//                 over an ensemble of jitters (sub-pixel offset, depth phase): onset distributions
//   sliver        sliver angle and size against coverage errors (exact path, no FMA, ablations)
//   far_distance  distance from the origin up to the viewportBoundsRange limit (exact path)
//   near_w        a vertex on the near plane with w approaching 0
//   non_finite    NaN and infinite vertex components
//   fill_*, clip_*, depth_far_near, pseudo_depth, coplanar_offset, visibility_*, line_*, cull_edge_on:
//                 the method maps of every family (method_maps.hpp), with their failure boundaries
//                 (failure_boundary.hpp)
// Output: stability.csv (appended per point), stability.json (thresholds), charts, index.html.
#pragma once

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/csv_log.hpp"
#include "experiments/failure_boundary.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/scene_make.hpp"
#include "experiments/sweep_common.hpp"

namespace rastercmp::experiments {

inline constexpr const char* kStabilityCsv = "stability.csv";

struct StabilityPoint {
  std::string experiment, case_name, method;
  double param_a = 0, param_b = 0;
  std::function<Scene()> make_scene;
  CpuOptions cpu;           // the method under test
  uint32_t decal_draw = 0;     // wrong_surface: the draw that should win (others: unused)
  bool wrong_surface = false;  // value_* = fraction of the decal's pixels it does not win (else covered pixels)
  int jitter = 0;              // fight_onset: the ensemble member (ensemble_jitter); 0 elsewhere
};

// fight_onset's ensemble size: jitters 0 .. onset_jitters - 1 at every point. A jitter's depth
// phase h moves the pair h * kOnsetDepthPhaseRange world units away from the eye: the standard
// mapping's float clip z ~ w has a 2^-18 grid at w in [32, 64), and w (A - 1), A - 1 ~ 1/R, moves
// by 2/R >= 2^-18 for far/near up to 5.2e5, so the vertices take every phase of that grid; the
// one-step onset ~ 1/w^2 moves by at most 7% (56 -> 58).
inline int onset_jitters(bool quick) { return quick ? 4 : 8; }
inline constexpr double kOnsetDepthPhaseRange = 2;

// One point measured against a reference render of the same scene (lavapipe in the sweep; the
// exact CPU path, which equals lavapipe bit for bit, in the device-free tests): the CSV row.
using ReferenceRender = std::function<RenderResult(const Scene&)>;
std::vector<std::string> measure_stability_point(const StabilityPoint& point, const ReferenceRender& reference);

std::vector<StabilityPoint> stability_plan(bool quick);
std::vector<std::string> stability_header();

// The fight_onset geometry (also used by the tests' analytic bound): plane 50 units away,
// rotated by 30 degrees, far plane 100.
inline constexpr double kOnsetAngleDeg = 30;

void run_stability_sweep(const SweepOptions& options);

// stability.json, charts and index.html from the CSV (stability_charts.cpp).
void write_stability_outputs(const std::string& dir);

// The smallest far/near ratio of a (case, separation, jitter) series at which the wrong surface
// wins anywhere on either backend; NaN when it never does. Case: format + mapping_suffix.
double fight_onset_ratio(const CsvTable& table, const std::string& case_name, const std::string& separation,
                         const std::string& jitter = "0");

// The onsets of a (case, separation) series over the jitter ensemble, sorted, a jitter that never
// fights as +infinity; quartiles by nearest rank (sorted[(k (J - 1) + 2) / 4] for k = 0..4), so
// every statistic is a grid value. `before_min`: the grid ratio before the smallest onset (NaN when
// that is the first), so the ensemble's onsets lie in (before_min, max].
struct OnsetDistribution {
  std::vector<double> onsets;
  double min = NAN, q1 = NAN, median = NAN, q3 = NAN, max = NAN, before_min = NAN;
  size_t never = 0;
};
OnsetDistribution fight_onset_distribution(const CsvTable& table, const std::string& case_name,
                                           const std::string& separation);

// The analytic onset of fight_onset / depth_far_near (failure_boundary.cpp): nullopt where theory
// puts none within far/near 10^6 (D32 reversed).
struct OnsetPrediction {
  double value = NAN;
  std::string formula;
};
std::optional<OnsetPrediction> predicted_onset(const std::string& case_name, double separation);

// One series of stability.json's "boundaries": the measured bracket (last_clean, boundary), the
// refused points and, where theory predicts the boundary (predicted_boundary), `predicted` beside
// `measured_low` / `measured_high` and whether it lies in the bracket.
nlohmann::ordered_json boundary_json(const FailureBoundary& b);

// The data of the limit charts (far_distance, near_w, non_finite): a coverage and a depth block,
// rows (x, parameter as written, mismatch). x is the parameter's place on a SymlogAxis of the
// experiment's parameters, or the row's index for non_finite (case=value categories).
std::vector<DataBlock> limit_blocks(const CsvTable& table, const std::string& experiment);

// The page table shown instead of a limit chart whose mismatches are all 0 (only_zeros): a header,
// then (case, method, parameter, coverage mismatch, depth mismatch, identical to lavapipe) per point.
std::vector<std::vector<std::string>> limit_zero_table(const CsvTable& table, const std::string& experiment);

}  // namespace rastercmp::experiments
