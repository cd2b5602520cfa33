// A persistent pool of worker threads for the fast path: run(job) calls job(0) on the calling
// thread and job(1..n-1) on the pool's threads, all at the same time, and returns when every call
// has returned (rethrowing the first exception). Unlike a task scheduler it guarantees that the
// calls run concurrently, which the small-triangle pipeline (band_pipeline.hpp) relies on: a
// worker may wait for a block that another worker is setting up.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace rastercmp::cpu::fast {

class WorkerPool {
 public:
  explicit WorkerPool(uint32_t workers);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  uint32_t workers() const { return uint32_t(threads_.size()) + 1; }
  void run(const std::function<void(uint32_t)>& job);

 private:
  void thread_loop(uint32_t index);
  void call(const std::function<void(uint32_t)>& job, uint32_t index);

  std::mutex run_mutex_;  // one run at a time
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(uint32_t)>* job_ = nullptr;
  uint64_t generation_ = 0;
  uint32_t pending_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
  std::vector<std::thread> threads_;
};

// The process's pool for this many workers, made on first use.
WorkerPool& worker_pool(uint32_t workers);

}  // namespace rastercmp::cpu::fast
