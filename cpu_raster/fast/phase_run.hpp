// How a phase of a fast render (render_fast.cpp) runs on the worker pool, and how its workers'
// and tasks' thread CPU times are kept when the render is profiled (RenderProfile,
// render_fast.hpp; the scaling model of `bench --scaling --model` projects from them).
#pragma once

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

// Times a queue phase's tasks when the render is profiled (PhaseTimes::tasks): run(i, w, f) calls
// f, task i taken by worker w; attach() hands the times to the phase that just ran.
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
    times_[i] = TaskTime{thread_cpu_seconds() - start, w};
  }
  void attach(FastFrame& frame) {
    if (on_ && !frame.profile->phases.empty()) frame.profile->phases.back().tasks = std::move(times_);
  }

 private:
  bool on_;
  std::vector<TaskTime> times_;
};

// Stored depth values keep the order the bounds rely on (tile_depth_bounds.hpp) in every draw.

}  // namespace rastercmp::cpu::fast
