// Failure boundaries of the method maps (issue 21 item 3): along one series (experiment, case,
// method), whose points run from the benign end of the parameter to the hard end, the boundary is
// the first parameter value whose measure (map_measure: mismatch against the reference, or the
// method's own wrong-surface fraction) exceeds 0, and the value before it the last clean one, so the true
// boundary lies between the two. Rows the method refused (not_supported) are counted, not measured.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "experiments/csv_log.hpp"
#include "model/scene.hpp"

namespace rastercmp::experiments {

struct FailureBoundary {
  std::string experiment, family, case_name, method;
  double boundary = NAN;    // first failing parameter value; NaN when no point fails
  double last_clean = NAN;  // the point before it; NaN when the first point fails already
  size_t points = 0, failing = 0, refused = 0;
  std::vector<double> refused_values;  // the parameters of the refused points, in plan order
};

// Where theory puts a series' boundary (docs/experiments.md "Method maps"), for the series that have
// a prediction: the D16/D24/D32 z-fighting onset far/near of depth_far_near (usual mapping), the
// pseudo-depth step per format and far plane, painter's first contact of the cyclic bars (0.081) and
// the interpenetration depth at the first pixel centre (0.0531), and the line and cull maps'
// (map_theory.hpp method_map_prediction). nullopt for every other series.
struct BoundaryPrediction {
  double value = NAN;
  std::string formula;  // how it was computed, in words
  // True where theory says the predicted value itself is clean (the smallest polygon offset that
  // separates a coplanar pair): the bracket is then (boundary, last_clean], closed at the clean end.
  bool clean_at_value = false;
};
std::optional<BoundaryPrediction> predicted_boundary(const std::string& experiment, const std::string& case_name,
                                                     const std::string& method);

// The measured bracket in increasing order (a descending sweep's first failing value is its low
// end) and whether the prediction lies in it (low < predicted <= high, or the reverse for a
// descending sweep: the true boundary lies after the last clean value).
struct BracketCheck {
  double measured_low = NAN, measured_high = NAN;
  bool in_bracket = false;
};
BracketCheck check_bracket(const FailureBoundary& b, double predicted, bool clean_at_value = false);

// coplanar_offset: by how many raw steps (UNORM integers, D32 float ulps) the decal's stored depth
// exceeds the base's at worst over the decal's pixels, both drawn alone without offset with the
// method's depth interpolation (the exact CPU path, which equals lavapipe): the rounding
// discrepancy of two triangulations of one plane that the offset has to overcome. Far/near 1000.
double coplanar_discrepancy_steps(DepthFormat format, const std::string& method);

// The measure of one row: "any_mismatch" = samples whose owner or raw depth differs from the
// reference (coverage_mismatch + depth_mismatch; "excess_mismatch" the same, but a series fails
// where it exceeds its value at the series' first measured point, not 0), otherwise the named
// column (value_cpu: the method's own wrong-surface fraction). NaN for a refused point.
double map_measure(const CsvTable& table, const std::vector<std::string>& row, const std::string& measure);

// Every series of every method map in the table (stability.csv read back), in file order.
std::vector<FailureBoundary> failure_boundaries(const CsvTable& table);

// The one series of a list; throws std::out_of_range when it is not there.
const FailureBoundary& find_boundary(const std::vector<FailureBoundary>& all, const std::string& experiment,
                                     const std::string& case_name, const std::string& method);

}  // namespace rastercmp::experiments
