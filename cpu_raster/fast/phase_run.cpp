#include "cpu_raster/fast/phase_run.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>

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
  PhaseTimes times{phase, std::vector<double>(workers, 0.0), {}, profiled_seconds(frame.serial_mark, phase_start)};
  frame.profile->serial_seconds += times.serial_before;
  const auto timed = [&](uint32_t w) {
    const double start = thread_cpu_seconds();
    job(w);
    times.worker_seconds[w] = profiled_seconds(start, thread_cpu_seconds());
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

PhaseSchedule schedule_phase(const PhaseTimes& phase) {
  PhaseSchedule schedule;
  std::vector<double> free = phase.worker_seconds;
  if (free.empty()) return schedule;
  for (const TaskTime& task : phase.tasks)
    if (task.worker < free.size()) free[task.worker] -= task.seconds;
  for (double& f : free) f = std::max(f, 0.0);
  for (const TaskTime& task : phase.tasks) {
    const auto first_free = std::min_element(free.begin(), free.end());
    *first_free += task.seconds;
    schedule.workers.push_back(uint32_t(first_free - free.begin()));
  }
  schedule.seconds = phase.tasks.empty() ? *std::max_element(phase.worker_seconds.begin(), phase.worker_seconds.end())
                                         : *std::max_element(free.begin(), free.end());
  return schedule;
}

double projected_seconds(const PhaseTimes& phase) { return schedule_phase(phase).seconds; }

double RenderProfile::serial_after() const {
  double before = 0;
  for (const PhaseTimes& phase : phases) before += phase.serial_before;
  return std::max(serial_seconds - before, 0.0);
}

double projected_seconds(const RenderProfile& profile) {
  double total = profile.serial_seconds;
  for (const PhaseTimes& phase : profile.phases) total += projected_seconds(phase);
  return total;
}

namespace {

double median_of(std::vector<double> values) {
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(mid), values.end());
  if (values.size() % 2 == 1) return values[mid];
  return (values[mid] + *std::max_element(values.begin(), values.begin() + std::ptrdiff_t(mid))) / 2;
}

bool same_shape(const RenderProfile& a, const RenderProfile& b) {
  if (a.phases.size() != b.phases.size()) return false;
  for (size_t p = 0; p < a.phases.size(); ++p) {
    const PhaseTimes &x = a.phases[p], &y = b.phases[p];
    if (x.phase != y.phase || x.worker_seconds.size() != y.worker_seconds.size() || x.tasks.size() != y.tasks.size())
      return false;
  }
  return true;
}

}  // namespace

RenderProfile median_profile(const std::vector<RenderProfile>& reps) {
  const bool shaped =
      std::all_of(reps.begin(), reps.end(), [&](const RenderProfile& r) { return same_shape(r, reps[0]); });
  if (!shaped) {
    std::vector<double> totals;
    for (const RenderProfile& r : reps) totals.push_back(projected_seconds(r));
    const double median = median_of(totals);
    size_t best = 0;
    for (size_t i = 1; i < reps.size(); ++i)
      if (std::abs(totals[i] - median) < std::abs(totals[best] - median)) best = i;
    return reps[best];
  }
  RenderProfile out;
  std::vector<double> values;
  const auto median_by = [&](const auto& value_of) {
    values.clear();
    for (const RenderProfile& r : reps) values.push_back(value_of(r));
    return median_of(values);
  };
  out.serial_seconds = median_by([](const RenderProfile& r) { return r.serial_seconds; });
  for (size_t p = 0; p < reps[0].phases.size(); ++p) {
    PhaseTimes phase{
        reps[0].phases[p].phase, {}, {}, median_by([p](const RenderProfile& r) { return r.phases[p].serial_before; })};
    const size_t workers = reps[0].phases[p].worker_seconds.size(), tasks = reps[0].phases[p].tasks.size();
    // each worker's time outside the phase's tasks (all of it in a phase without tasks)
    const auto outside = [p](const RenderProfile& r, size_t w) {
      const PhaseTimes& of = r.phases[p];
      double t = of.worker_seconds[w];
      for (const TaskTime& task : of.tasks)
        if (task.worker == w) t -= task.seconds;
      return std::max(t, 0.0);
    };
    for (size_t w = 0; w < workers; ++w)
      phase.worker_seconds.push_back(median_by([&](const RenderProfile& r) { return outside(r, w); }));
    for (size_t i = 0; i < tasks; ++i)  // no worker: their times are not in worker_seconds
      phase.tasks.push_back(
          {median_by([&](const RenderProfile& r) { return r.phases[p].tasks[i].seconds; }), UINT32_MAX});
    out.phases.push_back(std::move(phase));
  }
  return out;
}

}  // namespace rastercmp::cpu::fast
