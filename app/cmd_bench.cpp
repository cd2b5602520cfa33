// rastercmp bench [--json FILE] [--reps N] [--scene NAME|FILE]... [--suite DIR] [--threads N]
//                 [--scaling [--model [--tasks N]] [--chart-dir DIR]]
// Times, in one run and interleaved rep by rep, the exact CPU path (threads = 0), the fast CPU path
// (threads = N, default 2) and lavapipe (submit to fence; instance, pipeline and resource creation
// and read-back excluded; LP_NUM_THREADS=2 unless set) on the benchmark scenes of
// bench/bench_scenes.hpp, on any scene file and on the whole built-in suite (docs/performance.md).
// --scaling times the fast path alone at 1, 2, 4, ... threads up to the host's cores and charts
// time against threads (gnuplot); with --model it projects 1 to 64 workers from each worker's
// thread CPU time per phase (bench_model.cpp), --tasks N listing each queue phase's tasks at N.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/bench_common.hpp"
#include "app/commands.hpp"
#include "app/options.hpp"
#include "bench/bench_scenes.hpp"
#include "bench/bench_stats.hpp"
#include "compare/case_select.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/render_fast.hpp"
#include "experiments/gnuplot.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/mesh_import.hpp"
#include "model/scene_io.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::app {
namespace {

using bench::TimingStats;

// The fast path over a case's scenes into `results` (one per scene) at options.threads: one after
// another, or side by side (BenchCase::side_by_side); seconds, each render (or the whole
// side-by-side run) timed by seconds_of. new_buffers: each render into new result buffers
// (render_cpu_fast; side by side: into `results`, which the caller leaves empty).
double time_fast_case(const std::vector<Scene>& scenes, bool side_by_side, const CpuOptions& options,
                      std::vector<RenderResult>& results, bool new_buffers);

struct Target {
  const char* scene;
  double must, aim;  // lavapipe time / fast CPU time
};
// The project's targets at two threads (docs/performance.md, "Current figures"); where no aim was
// set beyond the must, the aim is the must.
constexpr Target kTargets[] = {{"fill_b2f", 4, 9},    {"fill_f2b", 8, 15},     {"grid_180k", 15, 25},
                               {"tiny_1m", 15, 25},   {"perspective", 10, 10}, {"lines_20k", 5, 10},
                               {"msaa4_grid", 5, 10}, {"suite", 10, 10}};

struct CaseReport {
  std::string name;
  uint64_t triangles = 0, fragments = 0, pixels = 0;
  // Seconds per rep, the case's scenes summed. fast: into the previous rep's buffers (as lavapipe
  // draws into attachments made by prepare); fast_alloc: into new buffers each time.
  std::vector<double> exact, fast, fast_alloc, lavapipe;
  uint64_t memory_exact = 0, memory_fast = 0, memory_lavapipe = 0;
  bool fast_equals_exact = true, fast_equals_lavapipe = true;
  std::vector<RenderResult> fast_results;  // one per scene, from the warm-up
};

// CPU seconds of the process's threads other than the calling one.
double other_threads_cpu_seconds() {
  rusage process{}, thread{};
  getrusage(RUSAGE_SELF, &process);
  getrusage(RUSAGE_THREAD, &thread);
  const auto seconds = [](const rusage& u) {
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  };
  return seconds(process) - seconds(thread);
}

// Timed calls start once the process's other threads have been idle for a millisecond (at most
// 100 ms of waiting): lavapipe's threads go on working after its fence signals (measured: an
// interleaved fast render of grid_180k took 8.4 ms against 4.5 ms alone, with the same CPU time).
void wait_until_other_threads_idle() {
  double before = other_threads_cpu_seconds();
  for (int round = 0; round < 100; ++round) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const double now = other_threads_cpu_seconds();
    if (now - before < 1e-4) return;
    before = now;
  }
}

double time_fast_case(const std::vector<Scene>& scenes, bool side_by_side, const CpuOptions& options,
                      std::vector<RenderResult>& results, bool new_buffers) {
  if (side_by_side)
    return seconds_of([&] { cpu::fast::render_fast_side_by_side(scenes, options, cpu::fast::FastConfig{}, results); });
  double total = 0;
  for (size_t i = 0; i < scenes.size(); ++i)
    total += new_buffers ? seconds_of([&] { render_cpu_fast(scenes[i], options); })
                         : seconds_of([&] { render_cpu_fast_into(scenes[i], options, results[i]); });
  return total;
}

bool same_bytes(const RenderResult& a, const RenderResult& b, bool compare_depth) {
  return a.owner == b.owner && (!compare_depth || a.depth_raw == b.depth_raw);
}

// Renders every scene once on each side (shader JIT, caches, the comparisons) and drops the scenes
// the CPU profile or the Vulkan device does not reproduce (NotSupported). Peak memory: the largest
// of the scenes' (fast path: one render, its result included; lavapipe: prepare and one submit).
std::vector<std::unique_ptr<VulkanRenderer::Prepared>> warm_up(BenchCase& c, VulkanRenderer& vulkan,
                                                               const CpuOptions& fast, CaseReport& report) {
  std::vector<std::unique_ptr<VulkanRenderer::Prepared>> prepared;
  std::vector<Scene> kept;
  for (Scene& scene : c.scenes) {
    try {
      RenderResult result;
      report.memory_fast =
          std::max(report.memory_fast, bench::peak_memory_delta([&] { result = render_cpu_fast(scene, fast); }));
      std::unique_ptr<VulkanRenderer::Prepared> p;
      report.memory_lavapipe = std::max(report.memory_lavapipe, bench::peak_memory_delta([&] {
                                          p = vulkan.prepare(scene);
                                          vulkan.submit_and_wait_seconds(*p);  // the JIT builds its variants
                                        }));
      const RenderResult reference = vulkan.read_back(*p);
      report.fast_equals_lavapipe &= same_bytes(reference, result, reference.has_depth());
      prepared.push_back(std::move(p));
      report.fast_results.push_back(std::move(result));
      kept.push_back(std::move(scene));
    } catch (const NotSupportedError&) {
    }
  }
  c.scenes = std::move(kept);
  return prepared;
}

CaseReport run_case(BenchCase& c, VulkanRenderer& vulkan, const BenchArgs& args, bool fma) {
  CpuOptions exact_options, fast_options;
  exact_options.fma = fast_options.fma = fma;
  // The release of the driver timed beside it, so that the renders can be held to its bytes.
  exact_options.lavapipe = fast_options.lavapipe = lavapipe_release_for_driver(vulkan.device().driver_info).release;
  fast_options.threads = args.threads;
  CaseReport report;
  report.name = c.name;
  std::vector<std::unique_ptr<VulkanRenderer::Prepared>> prepared = warm_up(c, vulkan, fast_options, report);
  const std::vector<RenderResult>& fast_results = report.fast_results;
  for (const Scene& scene : c.scenes) {
    report.triangles += bench::triangle_count(scene);
    report.fragments += bench::covered_samples(scene, fma);
    report.pixels += uint64_t(scene.width) * scene.height * scene.samples;
  }
  for (unsigned rep = 0; rep < args.reps; ++rep) {
    double fast = 0, fast_alloc = 0, lavapipe = 0, exact = 0;
    const auto time_fast = [&] {
      fast += time_fast_case(c.scenes, c.side_by_side, fast_options, report.fast_results, false);
      std::vector<RenderResult> fresh(c.scenes.size());
      fast_alloc += time_fast_case(c.scenes, c.side_by_side, fast_options, fresh, true);
    };
    const auto time_lavapipe = [&] {
      for (auto& p : prepared) {
        wait_until_other_threads_idle();  // as in seconds_of
        lavapipe += vulkan.submit_and_wait_seconds(*p);
      }
    };
    if (rep % 2 == 0)
      time_fast(), time_lavapipe();  // alternate the order: neither always goes first
    else
      time_lavapipe(), time_fast();
    report.fast.push_back(fast);
    report.fast_alloc.push_back(fast_alloc);
    report.lavapipe.push_back(lavapipe);
    if (rep >= args.exact_reps) continue;
    const auto time_exact = [&] {
      for (size_t i = 0; i < c.scenes.size(); ++i) {
        RenderResult result;
        exact += seconds_of([&] { result = render_cpu(c.scenes[i], exact_options); });
        if (rep == 0) report.fast_equals_exact &= same_bytes(result, fast_results[i], true);
      }
    };
    if (rep == 0)
      report.memory_exact = bench::peak_memory_delta(time_exact);
    else
      time_exact();
    report.exact.push_back(exact);
  }
  return report;
}

std::string ms(const TimingStats& s) {
  return s.count ? fmt::format("{:.2f} [{:.2f}-{:.2f}]", s.median * 1e3, s.min * 1e3, s.max * 1e3) : "-";
}
double rate(uint64_t count, const TimingStats& s) { return s.median > 0 ? double(count) / s.median * 1e-6 : 0; }
double mib(uint64_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

void print_table(const std::vector<CaseReport>& reports, const BenchArgs& args, const bench::LoadMonitor& load,
                 bool memory_kept) {
  fmt::print(
      "\nmedian ms [min-max] over {} reps ({} for the exact path); fast CPU path: {} thread(s); lavapipe: "
      "LP_NUM_THREADS={}; freed memory kept by the allocator: {}\n\n",
      args.reps, args.exact_reps, args.threads, std::getenv("LP_NUM_THREADS"), memory_kept ? "yes" : "no");
  fmt::print("CPU: {} ({} hardware threads, {} usable), fast path kernels: {}\n\n", cpu_model(),
             std::thread::hardware_concurrency(), host_usable_cpus(), fast_kernels());
  fmt::print(
      "| scene | tris | frags | exact ms | fast ms | fast+alloc ms | lavapipe ms | lvp/fast | lvp/exact | fast "
      "Mtri/s | fast Mpix/s | lvp Mtri/s | lvp Mpix/s | peak MiB exact/fast/lvp | same bytes exact/lvp |\n");
  fmt::print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
  for (const CaseReport& r : reports) {
    const TimingStats e = bench::summarize(r.exact), f = bench::summarize(r.fast), l = bench::summarize(r.lavapipe);
    fmt::print(
        "| {} | {} | {} | {} | {} | {} | {} | {:.1f}x | {:.2f}x | {:.1f} | {:.1f} | {:.1f} | {:.1f} | "
        "{:.0f}/{:.0f}/{:.0f} | {}/{} |\n",
        r.name, r.triangles, r.fragments, ms(e), ms(f), ms(bench::summarize(r.fast_alloc)), ms(l), l.median / f.median,
        e.median > 0 ? l.median / e.median : 0, rate(r.triangles, f), rate(r.fragments, f), rate(r.triangles, l),
        rate(r.fragments, l), mib(r.memory_exact), mib(r.memory_fast), mib(r.memory_lavapipe),
        r.fast_equals_exact ? "yes" : "NO", r.fast_equals_lavapipe ? "yes" : "NO");
  }
  fmt::print(
      "\nload: other processes kept {:.2f} of the cores busy on average (1-min load average {:.2f}), this run "
      "{:.2f}, over {:.1f} s\n\n",
      load.other_cores(), load.load_average_1min(), load.own_cores(), load.wall_seconds());
  for (const Target& t : kTargets) {
    for (const CaseReport& r : reports) {
      if (r.name != t.scene) continue;
      const double ratio = bench::summarize(r.lavapipe).median / bench::summarize(r.fast).median;
      fmt::print("target {:<12} lavapipe/fast {:6.1f}x   must reach {:4.0f}x: {}   aim {:4.0f}x: {}\n", t.scene, ratio,
                 t.must, ratio >= t.must ? "reached" : "NOT REACHED", t.aim, ratio >= t.aim ? "reached" : "not yet");
    }
  }
}

nlohmann::ordered_json stats_json(const std::vector<double>& samples) {
  const TimingStats s = bench::summarize(samples);
  std::vector<double> samples_ms;
  for (double x : samples) samples_ms.push_back(x * 1e3);
  return {{"reps", s.count},       {"median_ms", s.median * 1e3}, {"q1_ms", s.q1 * 1e3},     {"q3_ms", s.q3 * 1e3},
          {"min_ms", s.min * 1e3}, {"max_ms", s.max * 1e3},       {"samples_ms", samples_ms}};
}

void write_json(const std::string& path, const std::vector<CaseReport>& reports, const BenchArgs& args,
                const bench::LoadMonitor& load, bool memory_kept) {
  nlohmann::ordered_json j;
  j["cpu_model"] = cpu_model();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  j["usable_cpus"] = host_usable_cpus();
  j["fast_kernels"] = fast_kernels();
  j["fast_threads"] = args.threads;
  j["lp_num_threads"] = std::getenv("LP_NUM_THREADS");
  j["freed_memory_kept"] = memory_kept;
  j["load"] = {{"other_cores", load.other_cores()},
               {"own_cores", load.own_cores()},
               {"loadavg_1min", load.load_average_1min()},
               {"wall_s", load.wall_seconds()}};
  for (const CaseReport& r : reports) {
    const auto target =
        std::find_if(std::begin(kTargets), std::end(kTargets), [&](const Target& t) { return t.scene == r.name; });
    j["scenes"].push_back(
        {{"name", r.name},
         {"target", target == std::end(kTargets)
                        ? nlohmann::ordered_json()
                        : nlohmann::ordered_json{{"must", target->must}, {"aim", target->aim}}},
         {"triangles", r.triangles},
         {"fragments", r.fragments},
         {"pixels", r.pixels},
         {"exact", stats_json(r.exact)},
         {"fast", stats_json(r.fast)},
         {"fast_new_buffers", stats_json(r.fast_alloc)},
         {"lavapipe", stats_json(r.lavapipe)},
         {"peak_bytes", {{"exact", r.memory_exact}, {"fast", r.memory_fast}, {"lavapipe", r.memory_lavapipe}}},
         {"fast_equals_exact", r.fast_equals_exact},
         {"fast_equals_lavapipe", r.fast_equals_lavapipe}});
  }
  std::ofstream out(path);
  if (!out) throw UsageError("--json " + path + ": cannot write the file");
  out << j.dump(2) << "\n";
}

// --scaling: the fast path alone, at 1, 2, 4, ... threads up to the CPUs it may use
// (host_usable_cpus, and that number itself), median of --reps renders into reused buffers per
// scene and count.
std::vector<uint32_t> scaling_threads() {
  const uint32_t cores = host_usable_cpus();
  std::vector<uint32_t> counts;
  for (uint32_t t = 1; t < cores; t *= 2) counts.push_back(t);
  counts.push_back(cores);
  return counts;
}

int run_scaling(const BenchArgs& args) {
  std::vector<BenchCase> cases = make_cases(args);
  const std::vector<uint32_t> counts = scaling_threads();
  CpuOptions options;
  options.fma = lavapipe_fuses_on_this_host();
  fmt::print("CPU: {} ({} hardware threads, {} usable), fast path kernels: {}\n", cpu_model(),
             std::thread::hardware_concurrency(), host_usable_cpus(), fast_kernels());
  fmt::print("fast path, median ms over {} reps (speed-up over 1 thread)\n\n| scene |", args.reps);
  for (uint32_t t : counts) fmt::print(" {} thr |", t);
  fmt::print("\n|---|");
  for (size_t i = 0; i < counts.size(); ++i) fmt::print("---:|");
  fmt::print("\n");
  nlohmann::ordered_json j;
  j["cpu_model"] = cpu_model();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  j["usable_cpus"] = host_usable_cpus();
  j["fast_kernels"] = fast_kernels();
  std::vector<experiments::DataBlock> blocks;
  std::string plot = "plot ";
  for (BenchCase& c : cases) {
    std::vector<Scene> kept;  // the scenes the CPU profile supports
    std::vector<RenderResult> results;
    keep_supported(c.scenes, options, kept, results);
    fmt::print("| {} |", c.name);
    experiments::DataBlock block{c.name, {{"threads", "ms", experiments::gp_quote(c.name)}}};
    nlohmann::ordered_json row{{"name", c.name}};
    double one = 0;
    for (uint32_t t : counts) {
      options.threads = t;
      std::vector<double> samples;
      for (unsigned rep = 0; rep < args.reps; ++rep)
        samples.push_back(time_fast_case(kept, c.side_by_side, options, results, false));
      const TimingStats s = bench::summarize(samples);
      if (t == 1) one = s.median;
      fmt::print(" {:.2f} ({:.1f}x) |", s.median * 1e3, s.median > 0 ? one / s.median : 0);
      std::fflush(stdout);
      block.rows.push_back({fmt::format("{}", t), fmt::format("{}", s.median * 1e3), "x"});
      row["threads"].push_back({{"threads", t}, {"fast", stats_json(samples)}});
    }
    fmt::print("\n");
    plot += fmt::format("DATA index {} using 1:2 title columnheader(3) with linespoints lw 2 pt 7, ", blocks.size());
    blocks.push_back(std::move(block));
    j["scenes"].push_back(std::move(row));
  }
  if (!args.json_path.empty()) {
    std::ofstream out(args.json_path);
    if (!out) throw UsageError("--json " + args.json_path + ": cannot write the file");
    out << j.dump(2) << "\n";
  }
  plot.resize(plot.size() - 2);
  const std::string body = "set title " +
                           experiments::gp_quote("fast path: time per render against threads (" + cpu_model() + ")") +
                           " noenhanced\nset logscale xy 2\nset xlabel 'threads'\nset ylabel 'ms (median)'\n"
                           "set key outside right top\nset grid\n" +
                           plot + "\n";
  write_chart(args.chart_dir, "bench_scaling", blocks, body);
  return kExitOk;
}

int run_bench(const BenchArgs& args) {
  if (args.tasks_at != 0 && !(args.scaling && args.model))
    throw UsageError("--tasks: expected with --scaling --model (the tasks are those of the model's renders)");
  // every mode times renders, not the page faults of memory the render before freed
  const bool memory_kept = bench::keep_freed_memory();
  if (args.scaling && args.model) return run_scaling_model(args);
  if (args.scaling) return run_scaling(args);
  setenv("LP_NUM_THREADS", "2", 0);         // before the device exists; an explicit setting wins
  std::optional<OutputFolder> json_folder;  // --json checked before the minutes of timing
  if (!args.json_path.empty()) json_folder.emplace(output_file_folder(args.json_path));
  std::vector<BenchCase> cases = make_cases(args);
  VulkanRenderer vulkan(VkOptions{});
  const bool fma = vulkan.device().is_lavapipe ? vulkan.device().fma : lavapipe_fuses_on_this_host();
  bench::LoadMonitor load;
  load.start();
  std::vector<CaseReport> reports;
  for (BenchCase& c : cases) {
    fmt::print(stderr, "bench: {} ...\n", c.name);
    reports.push_back(run_case(c, vulkan, args, fma));
  }
  load.stop();
  print_table(reports, args, load, memory_kept);
  if (!args.json_path.empty()) write_json(args.json_path, reports, args, load, memory_kept);
  if (json_folder) json_folder->keep();
  for (const CaseReport& r : reports)
    if (!r.fast_equals_exact || !r.fast_equals_lavapipe) return kExitMismatch;
  return kExitOk;
}

}  // namespace

// Shared with the scaling model (bench_common.hpp, bench_model.cpp).
std::string cpu_model() { return host_cpu_model(); }

const char* fast_kernels() {
  return cpu::fast::host_has_avx512() ? "avx512" : cpu::fast::host_has_avx2_fma() ? "avx2" : "scalar";
}

double seconds_of(const std::function<void()>& run) {
  wait_until_other_threads_idle();
  const auto start = std::chrono::steady_clock::now();
  run();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void keep_supported(std::vector<Scene>& scenes, const CpuOptions& options, std::vector<Scene>& kept,
                    std::vector<RenderResult>& results) {
  for (Scene& scene : scenes) {
    try {
      results.push_back(render_cpu_fast(scene, options));
      kept.push_back(std::move(scene));
    } catch (const NotSupportedError&) {
    }
  }
}

std::vector<BenchCase> make_cases(const BenchArgs& args) {
  std::vector<std::string> names = args.scenes;
  if (names.empty()) {
    names = bench::standard_bench_scene_names();
    names.push_back("suite");
  }
  std::vector<BenchCase> cases;
  const std::vector<std::string> standard = bench::standard_bench_scene_names();
  for (const std::string& name : names) {
    if (name == "suite")
      cases.push_back(
          {name, bench::load_scene_suite(args.suite_dir.empty() ? default_suite_dir() : args.suite_dir), true});
    else if (std::find(standard.begin(), standard.end(), name) == standard.end() &&
             (name.ends_with(".json") || std::filesystem::is_regular_file(name)))  // a scene file, named by its stem
      cases.push_back({std::filesystem::path(name).stem().string(), {load_scene_or_model(name)}});
    else
      cases.push_back({name, {bench::standard_bench_scene(name).scene}});
  }
  return cases;
}

void write_chart(const std::string& dir, const std::string& name, const std::vector<experiments::DataBlock>& blocks,
                 const std::string& body) {
  std::filesystem::create_directories(dir);
  experiments::render_chart(dir, name, blocks, body);
  fmt::print("\nchart: {}/{}.svg and .png\n", dir, name);
}

void add_bench_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand("bench", "time the exact CPU path, the fast CPU path and lavapipe, interleaved");
  cmd->add_option("--json", args->json_path, "also write every sample and summary to this JSON file");
  cmd->add_option("--reps", args->reps, "timed repetitions per scene (fast path and lavapipe)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--exact-reps", args->exact_reps, "timed repetitions of the exact path (at most --reps)");
  cmd->add_option("--scene", args->scenes,
                  "fill_b2f, fill_f2b, grid_180k, tiny_1m, perspective, lines_20k, msaa4_grid, engine_1080p, suite, "
                  "lines_<L>px[_<A>deg] (20,000 lines of L px at A degrees or at random, in a 512 px frame) or a scene "
                  "or model file (repeatable)");
  cmd->add_option("--suite", args->suite_dir, "suite folder for the suite row (default: the built-in scenes/)");
  cmd->add_option("--threads", args->threads, "threads of the fast CPU path")->check(CLI::Range(1, 64));
  cmd->add_flag("--scaling", args->scaling,
                "time the fast path alone at 1, 2, 4, ... threads up to the host's and chart time against threads");
  cmd->add_flag("--model", args->model,
                "with --scaling: render with 1, 2, 4, ..., 64 threads on the cores there are and project each N's time "
                "on N cores from every worker's thread CPU time per phase");
  cmd->add_option("--tasks", args->tasks_at,
                  "with --scaling --model: print each queue phase's tasks at N workers (1, 2, 4, ..., 64): their "
                  "count, CPU time summed, the largest and each one's time in queue order, and the calling thread's "
                  "serial time before each phase (also in --json)")
      ->check(CLI::IsMember(kModelWorkers));
  cmd->add_option("--chart-dir", args->chart_dir, "folder of the --scaling chart (default bench-scaling)");
  cmd->callback([args, &exit_code] { exit_code = run_bench(*args); });
}

}  // namespace rastercmp::app
