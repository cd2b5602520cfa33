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

// Renders map_<experiment> for every experiment in the table and returns the page sections, each
// with its table of failure boundaries (method_map_charts.cpp).
std::vector<PageSection> write_method_map_charts(const std::string& dir, const CsvTable& table);

}  // namespace rastercmp::experiments
