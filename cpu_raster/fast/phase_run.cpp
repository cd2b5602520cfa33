#include "cpu_raster/fast/phase_run.hpp"

#include <algorithm>
#include <atomic>

#include "cpu_raster/fast/worker_pool.hpp"

namespace rastercmp::cpu::fast {

void run_phase(FastFrame& frame, const char* phase, uint32_t workers, const std::function<void(uint32_t)>& job) {
  const auto dispatch = [workers](const std::function<void(uint32_t)>& f) {
    if (workers == 1)
      f(0);
    else
      worker_pool(workers).run(f);
  };
  if (frame.profile == nullptr) {
    dispatch(job);
    return;
  }
  const uint32_t threads = frame.profile_threads > 0 ? std::min(workers, frame.profile_threads) : workers;
  // The calling thread's time since the last phase is serial; its time inside the pool's run
  // outside job(0) (waking the others, spinning until they finish) belongs to no phase: on N free
  // cores it would overlap the busiest worker's.
  const double phase_start = thread_cpu_seconds();
  frame.profile->serial_seconds += phase_start - frame.serial_mark;
  PhaseTimes times{phase, std::vector<double>(workers, 0.0), {}};
  const auto timed = [&](uint32_t w) {
    const double start = thread_cpu_seconds();
    job(w);
    times.worker_seconds[w] = thread_cpu_seconds() - start;
  };
  if (threads == workers) {
    dispatch(timed);
  } else {
    std::atomic<uint32_t> next{0};
    const std::function<void(uint32_t)> jobs = [&](uint32_t) {
      for (uint32_t w = next++; w < workers; w = next++) timed(w);
    };
    if (threads == 1)
      jobs(0);
    else
      worker_pool(threads).run(jobs);
  }
  frame.profile->phases.push_back(std::move(times));
  frame.serial_mark = thread_cpu_seconds();
}

double projected_seconds(const PhaseTimes& phase) {
  std::vector<double> free = phase.worker_seconds;
  if (free.empty()) return 0;
  if (phase.tasks.empty()) return *std::max_element(free.begin(), free.end());
  for (const TaskTime& task : phase.tasks)
    if (task.worker < free.size()) free[task.worker] -= task.seconds;
  for (double& f : free) f = std::max(f, 0.0);
  for (const TaskTime& task : phase.tasks) *std::min_element(free.begin(), free.end()) += task.seconds;
  return *std::max_element(free.begin(), free.end());
}

}  // namespace rastercmp::cpu::fast
