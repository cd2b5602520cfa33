// A persistent pool of worker threads for the fast path: run(job) calls job(0) on the calling
// thread and job(1..n-1) on the pool's threads, all at the same time (a job its thread has not
// taken when job(0) returns: on the calling thread after it; no job may wait for another), and
// returns when every call has returned (rethrowing the first exception). Made once per thread count and kept: a TBB
// task_arena made per render did not get its worker back after the first render (measured,
// docs/performance.md), and the workers here are long, equal jobs that need no stealing.
// The pool's threads are kept off the CPU the caller runs on (Linux affinity, recomputed when the
// caller moves): woken right after other threads of the process were busy, a pool thread was
// otherwise placed on the caller's CPU and the two workers shared one core for the whole render
// (measured: 13.8 ms instead of 7.0 ms for two 7 ms jobs).
// A render runs the pool once per phase (render_fast.cpp's phases). Waking a thread that sleeps
// cost 0.2-0.5 ms per run in this VM (measured, docs/performance.md), so a pool thread that has
// finished a job first spins for up to kSpinMicros on the atomic counters before it sleeps, and
// the caller waiting for the others for up to kCallerSpinMicros: it has nothing else to do, and
// once asleep it woke 0.1-0.2 ms after the last worker finished (perspective after a lavapipe
// render, a worker 120 us behind the caller: 0.86-0.93 ms a render with 100 us, 0.73 with 1 ms;
// docs/performance-log.md, 134c834). A thread that finds the next job while spinning, and one that
// counts itself off a run, takes no lock, so that on 16 cores the 15 threads of a phase do not
// queue for one mutex at its start and end; a thread that sleeps blocks on a condition variable.
// The pool also keeps each worker's pace in the band phase of the renders before (record_pace,
// relative_speeds): a worker whose core another process shares finishes the same work later, and
// the next render's static rows are shared out by it (row_balance.hpp). Which worker draws a row
// changes no byte, and neither does which thread runs job(i): a pool thread that has not taken
// its job by the time the caller has finished job(0) (asleep, or off its core while another
// process runs there) has it run by the caller instead (`claimed_`). Beside `stress-ng --cpu 1`
// the caller otherwise waited 0.8-1.0 ms for such a thread in 3-6% of the runs (a timing build,
// perspective and tiny_1m); on an idle host the threads have their jobs first.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace rastercmp::cpu::fast {

class WorkerPool {
 public:
  static constexpr int kSpinMicros = 100;
  static constexpr int kCallerSpinMicros = 1000;

  explicit WorkerPool(uint32_t workers);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  uint32_t workers() const { return uint32_t(threads_.size()) + 1; }
  void run(const std::function<void(uint32_t)>& job);

  // A band phase measured: worker w was given `work[w]` (the row estimate's units) and finished
  // `seconds[w]` after the phase began. Phases shorter than kPaceMinSeconds (waking and timer
  // noise) and workers given no work are left out. Each worker's pace (seconds a unit of work): a
  // slower one than it had is taken at once, a faster one smoothed over the phases
  // (kPaceSmoothing, the new measurement's share; a mean of paces, not of rates). A thread that
  // shares its core with another process often runs its whole band before the scheduler hands the
  // core back, and waits a slice in the next render: beside a busy loop lines_20k's 5 rows of 16
  // took 2.9 or 6.7-6.9 ms from one render to the next, and the smoothed pace swung the split
  // between 11/5 and 10/6 rows. Kept at its slow readings, the thread keeps the smaller share
  // (docs/performance-log.md, "A slower pace at once").
  static constexpr double kPaceMinSeconds = 1e-3;
  static constexpr double kPaceSmoothing = 0.5;
  void record_pace(const std::vector<double>& work, const std::vector<double>& seconds);
  // Each worker's rate over the fastest's, in [kPaceSlowest, 1]; all exactly 1 until every worker
  // has a rate, and while no rate is below kPaceEven of the fastest (a few percent between
  // equal workers is noise, and equal speeds keep the assignment of an idle host).
  static constexpr double kPaceEven = 0.8;
  static constexpr double kPaceSlowest = 0.2;
  std::vector<double> relative_speeds() const;
  // Forgets every pace measured: equal speeds until each worker is measured again.
  void reset_pace();

 private:
  void thread_loop(uint32_t index);
  void call(const std::function<void(uint32_t)>& job, uint32_t index);
  void keep_off_caller_cpu();
  void stop_workers();  // stops and joins every thread started

  std::mutex run_mutex_;  // one run at a time
  // A run publishes job_ and pending_ and increments generation_ (release), under mutex_. Job i of
  // generation g is claimed once, by thread i or by the caller, by moving claimed_[i - 1] to g
  // (compare-exchange, acq_rel; a value at or past g: claimed already); whoever claims it runs it
  // and decrements pending_ (acq_rel); a thread that brings it to 0 wakes the caller on done_
  // under mutex_. The next run starts only after every job of this one has counted itself off, so
  // job_ is this run's while a claim of this generation can still succeed.
  std::mutex mutex_;
  std::condition_variable start_, done_;
  std::atomic<const std::function<void(uint32_t)>*> job_{nullptr};
  std::atomic<uint32_t> generation_{0};
  std::atomic<uint32_t> pending_{0};
  std::unique_ptr<std::atomic<uint32_t>[]> claimed_;  // [i - 1]: the last generation whose job i is claimed
  std::atomic<bool> stop_{false};
  std::exception_ptr error_;  // the first job's exception of a run, under mutex_
  std::vector<std::thread> threads_;
  int placed_for_cpu_ = -1;  // the caller's CPU the threads' affinity was last set for
  mutable std::mutex pace_mutex_;
  std::vector<double> pace_;  // per worker, seconds a unit of work; 0 until measured
};

// The process's pool for this many workers, made on first use.
WorkerPool& worker_pool(uint32_t workers);

}  // namespace rastercmp::cpu::fast
