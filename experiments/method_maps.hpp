// The method maps of `sweep stability` (issue 21 item 3): for each family of the lecture notes'
// methods, a sweep of the parameter where the notes say the family fails, every method of the
// family at every point, mismatch against the reference per point. Each experiment's points run
// in plan order from the benign end to the hard end, so a method's failure boundary is the first
// parameter value whose measure exceeds 0 (failure_boundary.hpp).
//   fill        fill_sliver_width, fill_fan, fill_distance (and the sliver heat map of stability.cpp)
//   clip        clip_near_w, clip_near_w_line, clip_near_cross
//   depth       depth_far_near (cases: format x clip-z mapping, scene_make.hpp DepthMapping), pseudo_depth,
//               coplanar_offset
//   visibility  visibility_cyclic, visibility_interpenetration
//   line        line_slope, line_end_offset, line_length (cases: the line modes bresenham, rectangular)
//   cull        cull_edge_on (cases: on_axis, off_axis, y_flip, near_clipped)
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "experiments/html_page.hpp"
#include "experiments/stability.hpp"

namespace rastercmp::experiments {

struct MapExperiment {
  std::string_view name, family;
  std::string_view parameter;  // axis label, in plan order from benign to hard
  std::string_view measure;    // failure_boundary.hpp map_measure: "any_mismatch" or "value_cpu" (> 0 is a failure),
                               // "excess_mismatch" (more than at the benign end is a failure)
  std::string_view notes;      // where the lecture notes (docs/methods.md) say the family fails
  bool linear_axis = false;    // chart the parameter on a linear axis (angles), not log / symlog
};

const std::vector<MapExperiment>& method_map_experiments();
const MapExperiment* find_map_experiment(std::string_view name);  // nullptr for other experiments

// The methods of a family: (label, options). Label "exact" or "STAGE=NAME" as --method spells it.
using NamedMethod = std::pair<std::string, CpuOptions>;
std::vector<NamedMethod> family_methods(std::string_view family);
std::vector<NamedMethod> fill_methods();  // the sliver heat map's methods too

// Appends every method map point (quick: a small grid, for the tests).
void add_method_maps(std::vector<StabilityPoint>& plan, bool quick);

// The pair of the pseudo_depth experiment for the method's far plane F (75, 750, 7500): the
// near-coplanar pair scaled by 0.8 F / 50 at distance 0.8 F, so every vertex's w lies in 25..F.
PairParams pseudo_depth_pair(double far_distance, DepthFormat format, double separation);

// The predictions of the line and cull maps (failure_boundary.hpp predicted_boundary asks here):
//   line_end_offset, Bresenham lines, line=dda and line=bresenham: the smallest end offset at which
//     the real line crosses half a pixel at a column between the ends, so that the pixel it passes
//     nearest (whose diamond it crosses) is no longer the one the integer line through the end
//     pixels picks: min over columns k of (round(y_k) + 0.5 - y_k) run / k, in sub-pixels.
std::optional<BoundaryPrediction> method_map_prediction(const std::string& experiment, const std::string& case_name,
                                                        const std::string& method);

// A series for which theory expects no boundary but marks a parameter value: cull_edge_on's
// cull=normal_dot_view, where the face turns edge-on to the eye's ray (cull_edge_on_deg: 90, or
// 90 - kCullOffAxisDeg off the axis; a test with V along the view axis would switch at 90). N.V with
// V from the eye has the sign of the projected area, so both tests switch there together and no
// sample differs; only snapping within about 0.01 degrees of it could part them, where the face
// covers no sample. y_flip: the negative viewport height reverses the window winding, which clip
// space cannot see, so every sample the face covers on either side differs. stability.json records
// `expected` and `expected_holds` beside the measured bracket; the chart draws `marked` dashed.
struct MapExpectation {
  double marked = NAN;
  std::string marked_label, expected;
  bool never_fails = true;  // false: fails wherever either side covers a sample (y_flip)
};
std::optional<MapExpectation> method_map_expectation(const std::string& experiment, const std::string& case_name,
                                                     const std::string& method);
// Whether a series holds its expectation: never_fails -> no failing point; otherwise every point
// at which the reference or the method covers a sample fails, and no other.
bool expectation_holds(const CsvTable& table, const FailureBoundary& b, const MapExpectation& expected);

// Renders map_<experiment> for every experiment in the table and returns the page sections, each
// with its table of failure boundaries (method_map_charts.cpp).
std::vector<PageSection> write_method_map_charts(const std::string& dir, const CsvTable& table);

}  // namespace rastercmp::experiments
