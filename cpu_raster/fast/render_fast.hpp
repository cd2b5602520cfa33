// The fast CPU path: the same bits as the exact path (cpu_raster/exact/render_exact.cpp), faster
// (docs/performance.md). render_cpu() dispatches here when options.threads >= 1.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cpu_raster/exact/cpu_options.hpp"
#include "model/render_result.hpp"

namespace rastercmp {

// options.threads worker threads (0 is taken as 1). A profile, method override or feature the
// fast path does not model is handed to the exact path (same result, exact speed).
RenderResult render_cpu_fast(const Scene& scene, const CpuOptions& options);

// The same into `result`, reusing its owner and depth buffers when they are large enough (as a
// Vulkan application reuses its attachments from frame to frame).
void render_cpu_fast_into(const Scene& scene, const CpuOptions& options, RenderResult& result);

namespace cpu::fast {

// Where the CPU time of one render went: per phase, each worker's thread CPU time
// (CLOCK_THREAD_CPUTIME_ID around its share of the phase), and the calling thread's time outside
// the phases. `bench --scaling --model` runs N workers on the cores there are and projects the
// time on N cores from it: the serial time plus, per phase, the busiest worker's.
// A phase whose workers take tasks from a shared queue (vertices, block rows) also records each
// task's time and the worker that ran it, in queue order: with more workers than cores, who ran
// which task depended on the scheduler here, so the phase is projected as the queue would run on N
// free cores (projected_seconds).
struct TaskTime {
  double seconds = 0;
  uint32_t worker = 0;
};
struct PhaseTimes {
  std::string phase;
  std::vector<double> worker_seconds;  // one per worker
  std::vector<TaskTime> tasks;         // queue phases: one per task, in queue order
  double serial_before = 0;            // the calling thread's time since the previous phase (or the start)
};
// The phase's time on as many free cores as it had workers: its busiest worker's time; for a queue
// phase, the queue's tasks handed in order to the first worker free (ties: the lower), each worker
// first busy for its time outside tasks (worker 0: the profile check beside the vertex phase).
double projected_seconds(const PhaseTimes& phase);
// The same with the worker each task goes to (a queue phase: workers[i] for tasks[i]).
struct PhaseSchedule {
  double seconds = 0;
  std::vector<uint32_t> workers;
};
PhaseSchedule schedule_phase(const PhaseTimes& phase);
struct RenderProfile {
  std::vector<PhaseTimes> phases;  // in the order they ran
  double serial_seconds = 0;       // the calling thread's time outside the phases
  // serial_seconds less every phase's serial_before: the time after the last phase
  double serial_after() const;
};
// The projected time of a render on as many free cores as it had workers: its serial time plus
// projected_seconds of each phase.
double projected_seconds(const RenderProfile& profile);
// One profile from several renders of the same scene on as many workers (reps): each time the
// median of the reps' (the serial time and its part before each phase; per phase each worker's,
// and for a queue phase each task's in queue order, each worker then holding the median of its
// time outside tasks). A time that one rep read long (the host took the core for a while) does not
// set a phase's projection, where in one rep's profile the longest task of a phase nearly always
// is one such. Reps whose phases, workers or tasks differ in number: the rep whose projection is
// the median's. reps not empty.
RenderProfile median_profile(const std::vector<RenderProfile>& reps);

// Knobs for tests and benchmarks; the defaults are what render_cpu_fast uses.
struct FastConfig {
  bool allow_avx2 = true;     // false: the scalar kernels even on an AVX2 host
  bool every_thread = false;  // true: options.threads workers even where one would do (tests)
  bool allow_avx512 = true;   // false: the AVX2 kernels even on an AVX-512 host
  // false: the attachments at the frame's width even where frame_row_pitch would spread their rows
  // over the L1's sets (tests compare both; the bytes are the same)
  bool spread_pitch = true;
  RenderProfile* profile = nullptr;  // filled when set (cleared first)
  // With a profile: at most this many threads run a phase's worker jobs, one job after another
  // (0: one thread per worker). bench --scaling --model sets the host's hardware threads, so that
  // N workers' jobs are measured without N threads taking turns on fewer cores.
  uint32_t profile_threads = 0;
};

void render_fast_into(const Scene& scene, const CpuOptions& options, const FastConfig& config, RenderResult& result);

// The row pitch, in pixels, of the attachments render_fast_into draws `scene` into (unless
// FastConfig::spread_pitch is off): spread_row_pitch (frame_memory.hpp) for a frame of one sample
// per pixel with a draw of lines, no draw of triangles and pitched attachments within
// kMaxPitchedBytes, its width otherwise.
uint32_t frame_row_pitch(const Scene& scene);

// Many scenes on options.threads workers side by side, as `conformance --jobs` renders a suite:
// the scenes that would take several workers (worker_count) first, one after another, each with
// all of them; then the others, each on one worker, the workers taking the next scene from a queue
// that holds them by estimated cost, largest first (samples + 16 per vertex; ties in the given
// order). results[i] is scenes[i]'s (reused as render_fast_into reuses it; resized to match).
// With config.profile, profiles[i] is scenes[i]'s profile (render i's own RenderProfile; its
// workers: 1 for a queued scene), and config.profile_threads caps the threads of the queue.
void render_fast_side_by_side(const std::vector<Scene>& scenes, const CpuOptions& options, const FastConfig& config,
                              std::vector<RenderResult>& results, std::vector<RenderProfile>* profiles = nullptr);
// The scenes render_fast_side_by_side queues (each on one worker) at options.threads, in queue order.
std::vector<size_t> side_by_side_queue(const std::vector<Scene>& scenes, const CpuOptions& options,
                                       const FastConfig& config);
RenderResult render_fast(const Scene& scene, const CpuOptions& options, const FastConfig& config);

}  // namespace cpu::fast
}  // namespace rastercmp
