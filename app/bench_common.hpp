// What `rastercmp bench` (cmd_bench.cpp) and its scaling model (bench_model.cpp) share: the
// options, the cases a run times, and the helpers both print and time with.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cpu_raster/exact/cpu_options.hpp"
#include "experiments/gnuplot.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp::app {

struct BenchArgs {
  std::string json_path;
  unsigned reps = 21;
  unsigned exact_reps = 3;  // the exact path takes seconds on the big scenes
  unsigned threads = 2;
  std::vector<std::string> scenes;  // empty: all standard scenes and the suite
  std::string suite_dir;            // empty: the built-in suite (default_suite_dir)
  bool scaling = false;             // the fast path alone at 1, 2, 4, ... threads
  bool model = false;               // with scaling: N workers' phase times projected to N cores
  uint32_t tasks_at = 0;            // with model: each queue phase's tasks printed at this N (0: none)
  std::string chart_dir = "bench-scaling";
};

// One row of the table: one scene, or the whole suite rendered once per rep.
struct BenchCase {
  std::string name;
  std::vector<Scene> scenes;
  // The suite: its scenes rendered side by side on the fast path's threads
  // (cpu::fast::render_fast_side_by_side), as `conformance --jobs` runs them, and timed together.
  bool side_by_side = false;
};

// The cases of args.scenes (every standard scene and the suite when none is named).
std::vector<BenchCase> make_cases(const BenchArgs& args);

// The scenes the fast path renders (those the CPU profile supports: NotSupportedError leaves one
// out) moved into `kept`, with their renders into `results` (each render's buffers, reused by the
// timed renders).
void keep_supported(std::vector<Scene>& scenes, const CpuOptions& options, std::vector<Scene>& kept,
                    std::vector<RenderResult>& results);

// The host's CPU (model/host.hpp) and the fast path's kernels on it.
std::string cpu_model();
const char* fast_kernels();

// Wall seconds of run(), started once the process's other threads have been idle a millisecond.
double seconds_of(const std::function<void()>& run);

// A --scaling chart DIR/NAME.{dat,gp,svg,png} (gnuplot), named on stdout.
void write_chart(const std::string& dir, const std::string& name, const std::vector<experiments::DataBlock>& blocks,
                 const std::string& body);

// The worker counts the scaling model projects (--tasks takes one of them).
extern const std::vector<uint32_t> kModelWorkers;

// --scaling --model (bench_model.cpp). Returns the exit code.
int run_scaling_model(const BenchArgs& args);

}  // namespace rastercmp::app
