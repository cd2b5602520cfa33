// How a phase of a fast render (render_fast.cpp) runs on the worker pool, and how its workers'
// and tasks' thread CPU times are kept when the render is profiled (RenderProfile,
// render_fast.hpp; the scaling model of `bench --scaling --model` projects from them).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "cpu_raster/fast/fast_frame.hpp"
#include "cpu_raster/fast/render_fast.hpp"
#include "model/host.hpp"

namespace rastercmp::cpu::fast {

// job(0) .. job(workers - 1) at once (job(0) on the calling thread; one worker: just job(0)),
// each one's thread CPU time recorded under `phase` when the render is profiled. Profiled with
// FastConfig::profile_threads below `workers`, that many threads run the jobs, each taking the next
// job not started: no job waits for another inside a phase, so any order gives the same bytes,
// and each job's time is measured without more threads than cores taking turns.
void run_phase(FastFrame& frame, const char* phase, uint32_t workers, const std::function<void(uint32_t)>& job);

// The thread CPU time from `start` to `end` (thread_cpu_seconds) less the clock's own cost in it
// (thread_cpu_clock_cost): the profile's intervals are its work's, not its clock's. A phase of
// 16 workers' short tasks read each task 0.5 us long with the clock in it, which one worker's
// render, a few intervals in all, does not (docs/performance.md, "Scaling model").
inline double profiled_seconds(double start, double end) {
  return std::max(0.0, end - start - thread_cpu_clock_cost());
}

// Times a queue phase's tasks when the render is profiled (PhaseTimes::tasks): run(i, w, f) calls
// f, task i taken by worker w; attach() hands the times to the phase that just ran, and takes the
// two clock readings of each task out of its worker's time.
class TaskTimes {
 public:
  TaskTimes(const FastFrame& frame, size_t tasks) : on_(frame.profile != nullptr) {
    if (on_) times_.resize(tasks);
  }
  template <class F>
  void run(size_t i, uint32_t w, F&& f) {
    if (!on_) return f();
    const double start = thread_cpu_seconds();
    f();
    times_[i] = TaskTime{profiled_seconds(start, thread_cpu_seconds()), w};
  }
  void attach(FastFrame& frame) {
    if (!on_ || frame.profile->phases.empty()) return;
    PhaseTimes& phase = frame.profile->phases.back();
    for (const TaskTime& task : times_) {
      if (task.worker >= phase.worker_seconds.size()) continue;
      double& worker = phase.worker_seconds[task.worker];
      worker = std::max(0.0, worker - 2 * thread_cpu_clock_cost());
    }
    phase.tasks = std::move(times_);
  }

 private:
  bool on_;
  std::vector<TaskTime> times_;
};

}  // namespace rastercmp::cpu::fast
