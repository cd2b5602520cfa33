// Google Benchmark binary rastercmp_bench_pool: what the fast path's WorkerPool costs to hand a
// phase out and collect it, outside the renderer (docs/performance.md, "Scaling model"). Each run
// gives every worker one job that spins `job_us` microseconds, so that every thread takes its own
// (the caller runs any job no thread has taken when its own returns).
//   Pool/back_to_back/workers:<w>   runs one after another, the pool's threads still spinning
//   Pool/after_sleep/workers:<w>    each run 2 ms after the one before (untimed), its threads asleep
// Manual time, one run an iteration: the time above job_us is the hand-out, the collection and,
// after a sleep, the waking of the threads.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <thread>

#include "cpu_raster/fast/worker_pool.hpp"

namespace rastercmp {
namespace {

constexpr double kJobMicros = 20.0;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void pool_run(benchmark::State& state, bool after_sleep) {
  cpu::fast::WorkerPool& pool = cpu::fast::worker_pool(uint32_t(state.range(0)));
  const auto job = [](uint32_t) {
    const auto start = std::chrono::steady_clock::now();
    while (seconds_since(start) * 1e6 < kJobMicros) {
    }
  };
  for (int i = 0; i < 100; ++i) pool.run(job);  // the threads started and placed
  for (auto _ : state) {
    if (after_sleep) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const auto start = std::chrono::steady_clock::now();
    pool.run(job);
    state.SetIterationTime(seconds_since(start));
  }
  state.counters["job_us"] = kJobMicros;
}

}  // namespace
}  // namespace rastercmp

int main(int argc, char** argv) {
  for (const bool after_sleep : {false, true})
    benchmark::RegisterBenchmark(after_sleep ? "Pool/after_sleep" : "Pool/back_to_back", rastercmp::pool_run,
                                 after_sleep)
        ->ArgName("workers")
        ->Arg(2)
        ->Arg(4)
        ->Arg(8)
        ->Arg(16)
        ->Unit(benchmark::kMicrosecond)
        ->UseManualTime();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
