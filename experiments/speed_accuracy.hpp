// `rastercmp chart speed-accuracy`: for each CPU method entry, time per frame over a scene set and
// the mismatch against lavapipe (coverage and depth separately); lavapipe's own time as a point.
// New methods join by adding a MethodEntry to speed_accuracy_entries().
#pragma once

#include <optional>
#include <string>
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
};

std::vector<MethodEntry> speed_accuracy_entries();

struct EntrySummary {
  std::string family, method;
  double seconds_per_frame = 0;  // sum over the scene set of each scene's median time
  double coverage_mismatch_pct = 0, depth_mismatch_pct = 0;
};

// Pareto front (fastest first) over (seconds, mismatch): indices of entries no other entry beats
// in both; `mismatch` picks the accuracy measure.
std::vector<size_t> pareto_front(const std::vector<EntrySummary>& entries, bool coverage);

struct SpeedAccuracyRun {
  std::vector<EntrySummary> entries;
  EntrySummary lavapipe;
};

void run_speed_accuracy(const SweepOptions& options);

// Charts, JSON and page (speed_accuracy_charts.cpp).
void write_speed_accuracy_outputs(const std::string& dir, const SpeedAccuracyRun& run);

}  // namespace rastercmp::experiments
