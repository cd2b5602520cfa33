// `rastercmp chart scene-needs`: for each scene of a suite, which pipeline stages it needs and which
// it skips (scene_needs.hpp), and, on a set of timing scenes, what each skipped stage saves: the
// exact path (threads = 0) with every work skip on against the same render with that skip off,
// interleaved (the order alternates per repetition), timed in thread CPU time (the exact path renders
// on the calling thread), as the median over repetitions of the ratio
// off / on with its order-statistics 95% interval (order_stats.hpp). A skip is timed only where the
// scene does not need its stage; where it does, the work is done either way.
// Output: scene_needs.csv (one row per suite scene), skip_savings.csv, scene_needs.json, charts
// suite_needs and skip_savings, index.html.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "experiments/gnuplot.hpp"
#include "experiments/scene_needs.hpp"
#include "experiments/sweep_common.hpp"
#include "model/scene.hpp"

namespace rastercmp::experiments {

inline constexpr const char* kSceneNeedsCsv = "scene_needs.csv";
inline constexpr const char* kSkipSavingsCsv = "skip_savings.csv";

// The timing scenes (name, scene): the work-skip benchmark's grid mesh with and without a depth
// attachment (every vertex inside), the perspective mesh (it crosses the clip planes), the house
// (bias, culling) and the line star; --quick takes a smaller grid.
std::vector<std::pair<std::string, Scene>> skip_timing_scenes(bool quick);

// The suite_needs chart's data: one row per pipeline stage (stage, scenes that need it, scenes that
// skip it), in pipeline_stages() order, with no header row (gnuplot would read one as data).
DataBlock suite_needs_block(const std::vector<StageNeeds>& needs);

// `suite`: (case name, scene) of every scene to report (the built-in suite from the command).
void run_scene_needs(const SweepOptions& options, const std::vector<std::pair<std::string, Scene>>& suite);

}  // namespace rastercmp::experiments
