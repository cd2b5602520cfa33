// `rastercmp chart speed-accuracy`: for each CPU method entry, time per frame over a scene set and
// the mismatch against lavapipe (coverage and depth separately); lavapipe's own time as a reference.
// New methods join by adding a MethodEntry to speed_accuracy_entries().
//
// Implementation tiers: the classic methods run on the scalar exact path with one stage swapped,
// the fast path runs SIMD kernels on worker threads. A front across tiers is the fast path alone in
// every family, which says nothing about the methods, so fronts are computed among the scalar tier
// only (the exact path and the classic methods); the fast path and lavapipe are drawn beside them
// as reference lines, never as front members.
//
// Timing: repetitions are interleaved, each one timing every entry of the set once (lavapipe
// included) in an order rotated per repetition, so drift and noise hit all alike. An entry's time
// per repetition is the sum over the set's scenes; its point is the median over the repetitions
// with the order-statistics 95% interval of that median (order_stats.hpp). Both wall time and CPU
// time are taken: the calling thread's CPU time for a scalar render (it runs on that thread alone),
// the process's for the fast path and lavapipe (their work runs on worker threads). Timed: the
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
  bool lines = false;                       // runs on the line scene set instead of the triangle one
};

// The two scene sets, by name: "triangles" (coplanar pair, house, sliver pair, mesh) and "lines"
// (a star of lines inside the frame, and lines that cross the viewport's edges, for the clippers).
std::vector<Scene> speed_accuracy_scenes(bool lines);

// 64 one-pixel lines at depths 0.2 .. 0.8 in a 256x256 frame, each crossing at least one edge of
// the viewport (some two, some none: wholly outside), in front of the eye and inside the depth
// planes, so that every line clipper of the notes, 2-D and 3-D, runs and does work on it.
Scene make_clipped_lines(uint32_t size, uint32_t lines);

std::vector<MethodEntry> speed_accuracy_entries();

// scalar: the exact path and the classic methods (threads = 0); fast: the fast path (threads >= 1);
// reference: lavapipe.
enum class Tier { Scalar, Fast, Reference };
const char* to_string(Tier tier);

struct EntrySummary {
  std::string family, method;
  double seconds_per_frame = 0;  // median over the repetitions of the wall time for the whole scene set
  double coverage_mismatch_pct = 0, depth_mismatch_pct = 0;
  double seconds_low = 0, seconds_high = 0, ci_coverage = 0;  // the median's interval (order_stats.hpp)
  Tier tier = Tier::Scalar;
  // CPU time, like the wall time: median and its interval; "thread" or "process" (see above).
  double cpu_seconds = 0, cpu_seconds_low = 0, cpu_seconds_high = 0;
  std::string cpu_clock = "thread";
  // The set's total per repetition, in the order the repetitions ran.
  std::vector<double> wall_runs = {}, cpu_runs = {};
};

// Run-to-run spread of repeated times: (max - min) / median; 0 for no values or a zero median.
double run_spread(const std::vector<double>& values);

// Pareto front (fastest first) over (seconds, mismatch): indices of entries no other entry beats
// in both; `coverage` picks the accuracy measure.
std::vector<size_t> pareto_front(const std::vector<EntrySummary>& entries, bool coverage);

// Across tiers: each family's front with the exact path's and the fast path's entries in it, as
// indices into `entries`, fastest first. Families "exact path" and "fast path" get no front of their
// own. It answers one question only, whether a classic method beats the fast path at all.
std::vector<std::pair<std::string, std::vector<size_t>>> family_pareto_fronts(const std::vector<EntrySummary>& entries,
                                                                              bool coverage);

// A front point and whether the run establishes it: its median's 95% interval overlaps neither the
// interval of the front point before or after it (their order is not established), nor that of a
// candidate off the front that is exactly as accurate (the front dropped that one on medians alone,
// as happens among the exact path's equally exact ablations).
struct FrontPoint {
  size_t entry = 0;  // index into the entries
  bool separated = true;
};
std::vector<FrontPoint> mark_separation(const std::vector<EntrySummary>& entries, const std::vector<size_t>& front,
                                        const std::vector<size_t>& candidates, bool coverage);

// The families that get a scalar-tier chart: those of scalar entries, first appearance first,
// without "exact path" (it is in every family's chart).
std::vector<std::string> scalar_families(const std::vector<EntrySummary>& entries);

// The scalar-tier front of one family: its scalar entries with the scalar "exact path" entries; an
// empty `family` takes every scalar entry (the set's overall scalar front). Fastest first.
std::vector<FrontPoint> scalar_front(const std::vector<EntrySummary>& entries, const std::string& family,
                                     bool coverage);

// Which time ranks the fronts and spans the charts' x axis. On a shared machine a scalar render's
// wall time also counts the time other processes held its core; its thread CPU time does not.
enum class FrontClock { Cpu, Wall };
const char* to_string(FrontClock clock);

// The entry with its time fields (median, interval, repetitions) taken from `clock`: the CPU
// time moved into seconds_per_frame / seconds_low / seconds_high / wall_runs, or unchanged for Wall,
// so that the fronts and charts rank by the chosen clock.
EntrySummary timed_by(const EntrySummary& e, FrontClock clock);

// Where and on what a run took place, for the JSON.
struct RunHost {
  std::string host = "unknown", cpu_model = "unknown", git_commit = "unknown";
  bool git_dirty = false;                    // the checkout had uncommitted changes
  double load_before = -1, load_after = -1;  // 1-minute load average; -1 when unreadable
  bool freed_memory_kept = false;            // SweepOptions::freed_memory_kept
};
// This host, its CPU model and the commit the binary was built from (loads left at -1).
RunHost current_run_host();
// The 1-minute load average; -1 when unreadable.
double run_load_average();


struct SceneSetRun {
  std::string name;  // "triangles" or "lines"
  std::vector<EntrySummary> entries;
  EntrySummary lavapipe;
  std::vector<std::pair<std::string, std::string>> left_out;  // entry ("family: method"), why it refused the set
};

struct SpeedAccuracyRun {
  std::vector<SceneSetRun> sets;
  int repeats = 0;
  RunHost host;
  FrontClock clock = FrontClock::Cpu;
};

// `repetitions` 0: 21, or 5 with options.quick.
void run_speed_accuracy(const SweepOptions& options, int repetitions = 0, FrontClock clock = FrontClock::Cpu);

// Charts, JSON and page (speed_accuracy_charts.cpp).
void write_speed_accuracy_outputs(const std::string& dir, const SpeedAccuracyRun& run);
std::string speed_accuracy_json(const SpeedAccuracyRun& run);

}  // namespace rastercmp::experiments
