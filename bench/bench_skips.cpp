// Google Benchmark binary rastercmp_bench_skips: what each work skip of the exact path buys
// (cpu_raster/work_skips.hpp; docs/cpu-raster.md "What each skip buys").
//   Skip/<skip>/<scene>  each iteration renders the scene twice on the exact path (threads = 0): once
//                        with every skip on and once with <skip> off (or all of them: "all"), in
//                        alternating order. Both are timed in thread CPU time, so that the other
//                        processes of a shared machine count less. Counters: on_ms, off_ms (mean per
//                        render) and ratio = off / on (> 1: the skip saves that much).
// The benchmark's own time is that of both renders (at least 2 s of iterations). The load average
// at the start is in the context, the one at the end on stderr.
// Use --benchmark_repetitions=N --benchmark_report_aggregates_only=true for medians and spread.
#include <benchmark/benchmark.h>


#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "bench/skip_scenes.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "model/host.hpp"

namespace rastercmp {
namespace {

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string line;
  std::getline(in, line);
  return line;
}

struct SkipCase {
  std::string name;  // which skip is turned off
  cpu::WorkSkips off;
};

SkipCase skip_off(const std::string& name) {
  SkipCase c{name, {}};
  if (name == "clip") c.off.clip_only_when_needed = false;
  if (name == "depth") c.off.depth_only_when_attached = false;
  if (name == "bias") c.off.bias_only_when_enabled = false;
  if (name == "edges32") c.off.edges32_when_box_fits = false;
  if (name == "all") c.off = cpu::WorkSkips{false, false, false, false};
  return c;
}

double timed_render(const Scene& scene, const CpuOptions& options) {
  const double start = thread_cpu_seconds();
  benchmark::DoNotOptimize(render_cpu(scene, options));
  return thread_cpu_seconds() - start;
}

void skip_ratio(benchmark::State& state, const Scene* scene, SkipCase skip) {
  CpuOptions on;
  on.fma = lavapipe_fuses_on_this_host();
  on.threads = 0;  // the exact path
  CpuOptions off = on;
  off.skips = skip.off;
  double on_total = 0, off_total = 0;
  bool on_first = true;
  for (auto _ : state) {
    if (on_first) {
      on_total += timed_render(*scene, on);
      off_total += timed_render(*scene, off);
    } else {
      off_total += timed_render(*scene, off);
      on_total += timed_render(*scene, on);
    }
    on_first = !on_first;
  }
  state.counters["on_ms"] = benchmark::Counter(on_total * 1e3, benchmark::Counter::kAvgIterations);
  state.counters["off_ms"] = benchmark::Counter(off_total * 1e3, benchmark::Counter::kAvgIterations);
  state.counters["ratio"] = on_total > 0 ? off_total / on_total : 0;
}

struct NamedScene {
  std::string name;
  Scene scene;
};

std::vector<NamedScene> bench_scenes() {
  using skip_scenes::MeshSpec;
  const auto mesh = [](const std::string& name, MeshSpec spec) {
    return NamedScene{name, skip_scenes::grid_mesh("rastercmp.bench.skips." + name, spec)};
  };
  // 1024x1024, every vertex inside the frustum, depth X8D24 LESS, bias off: cells of ~3.8 px
  // (131072 triangles), ~30 px (2048) and ~122 px (128, boxes too big for 32-bit edges).
  return {
      mesh("small", MeshSpec{1024, 256}),
      mesh("medium", MeshSpec{1024, 32}),
      mesh("large", MeshSpec{1024, 8}),
      mesh("small_depthless", MeshSpec{1024, 256, 0.95f, DepthFormat::None}),
      mesh("medium_depthless", MeshSpec{1024, 32, 0.95f, DepthFormat::None}),
  };
}

}  // namespace
}  // namespace rastercmp

int main(int argc, char** argv) {
  using namespace rastercmp;
  static const std::vector<NamedScene> scenes = bench_scenes();
  const auto scene = [&](const std::string& name) -> const Scene* {
    for (const NamedScene& s : scenes)
      if (s.name == name) return &s.scene;
    return nullptr;
  };
  const std::vector<std::pair<std::string, std::vector<std::string>>> plan = {
      {"clip", {"small", "medium"}}, {"depth", {"small_depthless", "medium_depthless"}},
      {"bias", {"small", "medium"}}, {"edges32", {"small", "medium", "large"}},
      {"all", {"small", "medium"}},
  };
  for (const auto& [skip, names] : plan)
    for (const std::string& name : names)
      benchmark::RegisterBenchmark(("Skip/" + skip + "/" + name).c_str(), skip_ratio, scene(name), skip_off(skip))
          ->Unit(benchmark::kMillisecond)
          ->MinTime(2.0);
  benchmark::AddCustomContext("loadavg_at_start", load_average());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::fprintf(stderr, "loadavg at the end: %s\n", load_average().c_str());
  return 0;
}
