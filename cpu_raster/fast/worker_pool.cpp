#include "cpu_raster/fast/worker_pool.hpp"

#include <immintrin.h>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <system_error>

#include "cpu_raster/exact/float_ops.hpp"
#include "model/errors.hpp"

namespace rastercmp::cpu::fast {
namespace {

// Spins (with pause) until done() or `micros` have passed; true when done() held.
template <class Done>
bool spin_until(Done done, int micros) {
  const auto limit = std::chrono::steady_clock::now() + std::chrono::microseconds(micros);
  for (uint32_t i = 1;; ++i) {
    if (done()) return true;
    _mm_pause();
    if ((i & 63) == 0 && std::chrono::steady_clock::now() > limit) return false;
  }
}

// Moves `slot` to generation g unless it is there or past it already (wrapping compare): true
// when this call claimed job g.
bool claim(std::atomic<uint32_t>& slot, uint32_t g) {
  uint32_t seen = slot.load(std::memory_order_relaxed);
  while (int32_t(seen - g) < 0)
    if (slot.compare_exchange_weak(seen, g, std::memory_order_acq_rel, std::memory_order_relaxed)) return true;
  return false;
}

}  // namespace

WorkerPool::WorkerPool(uint32_t workers)
    : claimed_(std::make_unique<std::atomic<uint32_t>[]>(workers > 0 ? workers - 1 : 0)) {
  try {
    for (uint32_t i = 1; i < workers; ++i) threads_.emplace_back([this, i] { thread_loop(i); });
  } catch (const std::system_error& e) {
    // A process or memory limit refused a thread: stop the ones started (a joinable std::thread
    // destroyed would end the process in std::terminate) and say so (exit 3).
    const size_t started = threads_.size();
    stop_workers();
    throw EnvironmentError("cannot start " + std::to_string(workers - 1) + " CPU worker threads (started " +
                           std::to_string(started) + ": " + e.what() +
                           "); use a smaller --threads or raise the process or memory limit (ulimit -u, ulimit -v)");
  }
}

WorkerPool::~WorkerPool() { stop_workers(); }

void WorkerPool::stop_workers() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
  }
  start_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void WorkerPool::call(const std::function<void(uint32_t)>& job, uint32_t index) {
  const DenormalsFlushed ftz_daz;  // every job renders: lavapipe's FTZ/DAZ in every thread (rules §7.10)
  try {
    job(index);
  } catch (...) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!error_) error_ = std::current_exception();
  }
}

void WorkerPool::keep_off_caller_cpu() {
#ifdef __linux__
  const int caller = sched_getcpu();
  if (caller < 0 || caller == placed_for_cpu_ || threads_.empty()) return;
  placed_for_cpu_ = caller;
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) != 0) return;
  CPU_CLR(caller, &allowed);
  if (CPU_COUNT(&allowed) == 0) return;  // one CPU: nowhere else to go
  for (std::thread& t : threads_) pthread_setaffinity_np(t.native_handle(), sizeof(allowed), &allowed);  // a hint
#endif
}

void WorkerPool::run(const std::function<void(uint32_t)>& job) {
  const std::lock_guard<std::mutex> serial(run_mutex_);
  keep_off_caller_cpu();
  uint32_t g = 0;
  {
    // Under mutex_: a thread going to sleep tests the generation under it (no lost wake-up).
    const std::lock_guard<std::mutex> lock(mutex_);
    error_ = nullptr;
    job_.store(&job, std::memory_order_relaxed);
    pending_.store(uint32_t(threads_.size()), std::memory_order_relaxed);
    g = generation_.fetch_add(1, std::memory_order_release) + 1;
  }
  start_.notify_all();  // no system call while no thread sleeps
  call(job, 0);
  // the jobs no thread has taken yet: run here rather than waited for
  for (uint32_t i = 1; i <= threads_.size(); ++i) {
    if (!claim(claimed_[i - 1], g)) continue;
    call(job, i);
    pending_.fetch_sub(1, std::memory_order_acq_rel);
  }
  const auto all_done = [this] { return pending_.load(std::memory_order_acquire) == 0; };
  const bool done = spin_until(all_done, kCallerSpinMicros);
  std::unique_lock<std::mutex> lock(mutex_);  // done_'s wait, and error_
  if (!done) done_.wait(lock, all_done);
  job_.store(nullptr, std::memory_order_relaxed);
  if (error_) std::rethrow_exception(error_);
}

void WorkerPool::thread_loop(uint32_t index) {
  uint32_t seen = 0;
  const auto started = [&] { return generation_.load(std::memory_order_acquire) != seen; };
  for (;;) {
    // A thread that sees the next run while spinning takes no lock; one that sleeps blocks on
    // start_ (a futex: woken, it preempts a process that shares its core, where a yielding wait
    // would queue behind it).
    if (!spin_until(started, seen != 0 ? kSpinMicros : 0)) {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, started);
    }
    if (stop_.load(std::memory_order_relaxed)) return;
    seen = generation_.load(std::memory_order_acquire);
    if (!claim(claimed_[index - 1], seen)) continue;  // the caller ran it
    call(*job_.load(std::memory_order_relaxed), index);
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      const std::lock_guard<std::mutex> lock(mutex_);  // the caller tests pending_ under it
      done_.notify_one();
    }
  }
}

void WorkerPool::record_pace(const std::vector<double>& work, const std::vector<double>& seconds) {
  if (work.size() != workers() || seconds.size() != workers()) return;
  if (*std::max_element(seconds.begin(), seconds.end()) < kPaceMinSeconds) return;
  const std::lock_guard<std::mutex> lock(pace_mutex_);
  pace_.resize(workers(), 0.0);
  for (size_t w = 0; w < pace_.size(); ++w) {
    if (!(work[w] > 0.0 && seconds[w] > 0.0)) continue;
    const double pace = seconds[w] / work[w];
    // slower: at once; faster: smoothed
    pace_[w] = pace_[w] > 0.0 && pace < pace_[w] ? (1.0 - kPaceSmoothing) * pace_[w] + kPaceSmoothing * pace : pace;
  }
}

std::vector<double> WorkerPool::relative_speeds() const {
  std::vector<double> speeds(workers(), 1.0);
  const std::lock_guard<std::mutex> lock(pace_mutex_);
  if (pace_.size() != speeds.size() || std::any_of(pace_.begin(), pace_.end(), [](double p) { return p <= 0.0; }))
    return speeds;
  const double fastest = *std::min_element(pace_.begin(), pace_.end());
  if (std::all_of(pace_.begin(), pace_.end(), [fastest](double p) { return fastest >= kPaceEven * p; })) return speeds;
  for (size_t w = 0; w < speeds.size(); ++w) speeds[w] = std::max(kPaceSlowest, fastest / pace_[w]);
  return speeds;
}

void WorkerPool::reset_pace() {
  const std::lock_guard<std::mutex> lock(pace_mutex_);
  pace_.clear();
}

WorkerPool& worker_pool(uint32_t workers) {
  static std::mutex mutex;
  static std::map<uint32_t, std::unique_ptr<WorkerPool>> pools;
  const std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<WorkerPool>& pool = pools[workers];
  if (!pool) pool = std::make_unique<WorkerPool>(workers);
  return *pool;
}

}  // namespace rastercmp::cpu::fast
