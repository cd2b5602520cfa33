// Google Benchmark binary (docs/performance.md): the benchmark scenes of
// bench/bench_scenes.hpp on the exact CPU path, the fast CPU path and lavapipe.
//   Exact/<scene>, Fast/<scene>/threads:<n>  wall time of render_cpu / render_cpu_fast_into (buffers reused)
//   FastNewBuffers/<scene>/threads:2         render_cpu_fast: new result buffers each time
//   FastSuite/threads:<n>                    render_cpu_fast_into on every supported scene of scenes/
//   Lavapipe/<scene>                         submit to fence (manual time; creation and read-back excluded)
//   Interleaved/<scene>                      each iteration one fast render and one lavapipe submit, in
//                                            alternating order; manual time = the fast render, counters
//                                            lavapipe_ms and ratio (lavapipe / fast) over the same iterations
// Use --benchmark_repetitions=N --benchmark_report_aggregates_only=true for medians and spread.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_scenes.hpp"
#include "bench/bench_stats.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/fast/render_fast.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp {
namespace {

VulkanRenderer* vulkan() {  // null without a Vulkan device: the lavapipe benchmarks then skip
  static std::unique_ptr<VulkanRenderer> renderer = [] {
    setenv("LP_NUM_THREADS", "2", 0);
    try {
      return std::make_unique<VulkanRenderer>(VkOptions{});
    } catch (const std::exception&) {
      return std::unique_ptr<VulkanRenderer>();
    }
  }();
  return renderer.get();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

CpuOptions cpu_options(uint32_t threads) {
  CpuOptions options;
  options.fma = lavapipe_fuses_on_this_host();
  options.threads = threads;
  return options;
}

void set_rates(benchmark::State& state, const Scene& scene) {
  state.counters["Mtri/s"] =
      benchmark::Counter(double(bench::triangle_count(scene)) * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}

void exact(benchmark::State& state, const Scene* scene) {
  for (auto _ : state) benchmark::DoNotOptimize(render_cpu(*scene, cpu_options(0)));
  set_rates(state, *scene);
}

void fast(benchmark::State& state, const Scene* scene) {  // into the previous iteration's buffers
  const CpuOptions options = cpu_options(uint32_t(state.range(0)));
  RenderResult result;
  for (auto _ : state) render_cpu_fast_into(*scene, options, result);
  set_rates(state, *scene);
}

void fast_new_buffers(benchmark::State& state, const Scene* scene) {
  const CpuOptions options = cpu_options(uint32_t(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(render_cpu_fast(*scene, options));
  set_rates(state, *scene);
}

// The built-in suite as `rastercmp bench` times it: every scene the CPU profile supports, once per
// iteration, each into its own reused buffers.
void fast_suite(benchmark::State& state) {
  const CpuOptions options = cpu_options(uint32_t(state.range(0)));
  std::vector<Scene> scenes;
  std::vector<RenderResult> results;
  for (Scene& scene : bench::load_scene_suite(RASTERCMP_SOURCE_DIR "/scenes")) {
    try {
      results.push_back(render_cpu_fast(scene, options));
      scenes.push_back(std::move(scene));
    } catch (const NotSupportedError&) {
    }
  }
  for (auto _ : state)
    for (size_t i = 0; i < scenes.size(); ++i) render_cpu_fast_into(scenes[i], options, results[i]);
}

void lavapipe(benchmark::State& state, const Scene* scene) {
  if (!vulkan()) return state.SkipWithError("no Vulkan device");
  const auto prepared = vulkan()->prepare(*scene);
  vulkan()->submit_and_wait_seconds(*prepared);  // shader variants
  for (auto _ : state) state.SetIterationTime(vulkan()->submit_and_wait_seconds(*prepared));
  set_rates(state, *scene);
}

void interleaved(benchmark::State& state, const Scene* scene) {
  if (!vulkan()) return state.SkipWithError("no Vulkan device");
  const auto prepared = vulkan()->prepare(*scene);
  vulkan()->submit_and_wait_seconds(*prepared);
  const CpuOptions options = cpu_options(2);
  RenderResult result;
  double fast_total = 0, lavapipe_total = 0;
  bool fast_first = true;
  for (auto _ : state) {
    double lavapipe_seconds = 0, fast_seconds = 0;
    if (!fast_first) lavapipe_seconds = vulkan()->submit_and_wait_seconds(*prepared);
    const auto start = std::chrono::steady_clock::now();
    render_cpu_fast_into(*scene, options, result);
    fast_seconds = seconds_since(start);
    if (fast_first) lavapipe_seconds = vulkan()->submit_and_wait_seconds(*prepared);
    fast_first = !fast_first;
    state.SetIterationTime(fast_seconds);
    fast_total += fast_seconds;
    lavapipe_total += lavapipe_seconds;
  }
  state.counters["lavapipe_ms"] = benchmark::Counter(lavapipe_total * 1e3, benchmark::Counter::kAvgIterations);
  state.counters["ratio"] = fast_total > 0 ? lavapipe_total / fast_total : 0;
}

}  // namespace
}  // namespace rastercmp

int main(int argc, char** argv) {
  using namespace rastercmp;
  // as `rastercmp bench`: no render pays page faults of memory the one before freed (bench_stats.hpp)
  const bool memory_kept = bench::keep_freed_memory();
  static const std::vector<bench::BenchScene> scenes = bench::standard_bench_scenes();
  for (const bench::BenchScene& s : scenes) {
    benchmark::RegisterBenchmark(("Exact/" + s.name).c_str(), exact, &s.scene)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
    benchmark::RegisterBenchmark(("Fast/" + s.name).c_str(), fast, &s.scene)
        ->ArgName("threads")
        ->Arg(1)
        ->Arg(2)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("FastNewBuffers/" + s.name).c_str(), fast_new_buffers, &s.scene)
        ->ArgName("threads")
        ->Arg(2)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("Lavapipe/" + s.name).c_str(), lavapipe, &s.scene)
        ->Unit(benchmark::kMillisecond)
        ->UseManualTime();
    benchmark::RegisterBenchmark(("Interleaved/" + s.name).c_str(), interleaved, &s.scene)
        ->Unit(benchmark::kMillisecond)
        ->UseManualTime();
  }
  benchmark::RegisterBenchmark("FastSuite", fast_suite)
      ->ArgName("threads")
      ->Arg(1)
      ->Arg(2)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("freed_memory_kept", memory_kept ? "yes" : "no");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
