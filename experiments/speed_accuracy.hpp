// `rastercmp chart speed-accuracy`: for each CPU method entry, time per frame over a scene set and
// the mismatch against lavapipe (coverage and depth separately); lavapipe's own time as a point.
// New methods join by adding a MethodEntry to speed_accuracy_entries().
// Timing (issue 21 item 4): repetitions are interleaved, each one timing every entry of the set once
// (lavapipe included) in an order rotated per repetition, so drift and noise hit all alike. An
// entry's time per repetition is the sum over the set's scenes; its point is the median over the
// repetitions with the order-statistics 95% interval of that median (order_stats.hpp). Timed: the
// CPU's render_cpu call (its frame buffers included: every CPU method allocates the same ones);
// lavapipe's submit-to-fence on a prepared frame. Not timed: building the scenes, the pipeline and
// buffer set-up of lavapipe (prepare), read-back, and the comparison.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cpu_raster/cpu_raster.hpp"
#include "experiments/sweep_common.hpp"

namespace rastercmp::experiments {

inline constexpr const char* kSpeedAccuracyCsv = "speed_accuracy.csv";

struct MethodEntry {
  std::string family;  // clipping, fill, depth interpolation, visibility, depth format, exact path, fast path...
  std::string method;  // a name for the chart
  CpuOptions cpu;
  std::optional<DepthFormat> depth_format;  // renders the scene set (both backends) with this format
  bool lines = false;  // runs on the line scene set instead of the triangle one
};

// The two scene sets, by name: "triangles" (coplanar pair, house, sliver pair, mesh) and "lines".
std::vector<Scene> speed_accuracy_scenes(bool lines);

std::vector<MethodEntry> speed_accuracy_entries();

struct EntrySummary {
  std::string family, method;
  double seconds_per_frame = 0;  // median over the repetitions of the time for the whole scene set
  double coverage_mismatch_pct = 0, depth_mismatch_pct = 0;
  double seconds_low = 0, seconds_high = 0, ci_coverage = 0;  // the median's interval (order_stats.hpp)
};

// Pareto front (fastest first) over (seconds, mismatch): indices of entries no other entry beats
// in both; `mismatch` picks the accuracy measure.
std::vector<size_t> pareto_front(const std::vector<EntrySummary>& entries, bool coverage);

// The Pareto front of each family: the family's entries with the exact path's and the fast path's
// (those two families are in every front), as indices into `entries`, fastest first. Families
// "exact path" and "fast path" get no front of their own.
std::vector<std::pair<std::string, std::vector<size_t>>> family_pareto_fronts(const std::vector<EntrySummary>& entries,
                                                                               bool coverage);

struct SceneSetRun {
  std::string name;  // "triangles" or "lines"
  std::vector<EntrySummary> entries;
  EntrySummary lavapipe;
};

struct SpeedAccuracyRun {
  std::vector<SceneSetRun> sets;
  int repeats = 0;
};

void run_speed_accuracy(const SweepOptions& options);

// Charts, JSON and page (speed_accuracy_charts.cpp).
void write_speed_accuracy_outputs(const std::string& dir, const SpeedAccuracyRun& run);

}  // namespace rastercmp::experiments
