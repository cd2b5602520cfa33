// rastercmp chart speed-accuracy [--out DIR] [--quick] [--reps N] [--clock cpu|wall]
// rastercmp chart scene-needs [--out DIR] [--quick]
// rastercmp chart depth-precision [--out DIR] [--quick] [--near N] [--far F]
// rastercmp chart resolution [--out DIR] [--quick]
// rastercmp chart summary [--out DIR] [--from DIR]...
#include <memory>
#include <string>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "bench/bench_stats.hpp"
#include "compare/case_select.hpp"
#include "experiments/depth_precision.hpp"
#include "experiments/resolution_sweep.hpp"
#include "experiments/skip_savings.hpp"
#include "experiments/speed_accuracy.hpp"
#include "experiments/summary_figure.hpp"
#include "model/errors.hpp"

namespace rastercmp::app {

void add_chart_command(CLI::App& app, int& exit_code) {
  CLI::App* chart = app.add_subcommand("chart", "measured charts: speed-accuracy, scene-needs, depth-precision, resolution, summary");
  chart->require_subcommand(1);
  auto options = std::make_shared<experiments::SweepOptions>();
  options->out_dir = "chart-speed-accuracy";
  CLI::App* cmd = chart->add_subcommand(
      "speed-accuracy",
      "time per frame against mismatch with lavapipe for every CPU method; scalar-tier Pareto front per family");
  cmd->add_option("--out", options->out_dir, "output folder (CSV, JSON, charts, index.html)")->capture_default_str();
  cmd->add_flag("--quick", options->quick, "fewer repetitions (seconds), as the tests run it");
  auto reps = std::make_shared<int>(0);
  cmd->add_option("--reps", *reps, "interleaved repetitions (default 21, 5 with --quick)")->check(CLI::Range(1, 1000));
  auto clock = std::make_shared<std::string>("cpu");
  cmd->add_option("--clock", *clock,
                  "the time that ranks the fronts: cpu (thread CPU time of a scalar render; process CPU time of the "
                  "fast path and lavapipe) or wall; both are recorded")
      ->check(CLI::IsMember({"cpu", "wall"}))
      ->capture_default_str();
  cmd->callback([options, reps, clock, &exit_code] {
    options->freed_memory_kept = bench::keep_freed_memory();  // timed renders, as `rastercmp bench` times them
    experiments::run_speed_accuracy(*options, *reps,
                                    *clock == "wall" ? experiments::FrontClock::Wall : experiments::FrontClock::Cpu);
    fmt::print("speed-accuracy chart → {}/index.html\n", options->out_dir);
    exit_code = kExitOk;
  });

  auto needs = std::make_shared<experiments::SweepOptions>();
  needs->out_dir = "chart-scene-needs";
  CLI::App* needs_cmd = chart->add_subcommand(
      "scene-needs",
      "which pipeline stages each built-in scene needs, and what each skipped stage saves on the exact path");
  needs_cmd->add_option("--out", needs->out_dir, "output folder (CSV, JSON, charts, index.html)")->capture_default_str();
  needs_cmd->add_flag("--quick", needs->quick, "smaller timing scenes, fewer repetitions (seconds)");
  needs_cmd->callback([needs, &exit_code] {
    std::vector<std::pair<std::string, Scene>> suite;
    for (SuiteCase& c : load_suite(default_suite_dir())) suite.push_back({c.name, std::move(c.scene)});
    needs->freed_memory_kept = bench::keep_freed_memory();
    experiments::run_scene_needs(*needs, suite);
    fmt::print("scene-needs chart → {}/index.html\n", needs->out_dir);
    exit_code = kExitOk;
  });

  auto precision = std::make_shared<experiments::SweepOptions>();
  precision->out_dir = "chart-depth-precision";
  auto planes = std::make_shared<experiments::DepthPlanes>();
  CLI::App* precision_cmd = chart->add_subcommand(
      "depth-precision",
      "the smallest eye-distance step that changes the stored depth, per format and depth mapping, measured on the "
      "exact path beside the analytic curve");
  precision_cmd->add_option("--out", precision->out_dir, "output folder (CSV, JSON, charts, index.html)")
      ->capture_default_str();
  precision_cmd->add_flag("--quick", precision->quick, "4 eye distances per decade instead of 10");
  precision_cmd->add_option("--near", planes->near_plane, "near plane (eye distance)")->capture_default_str();
  precision_cmd->add_option("--far", planes->far_plane, "far plane (eye distance)")->capture_default_str();
  precision_cmd->callback([precision, planes, &exit_code] {
    experiments::run_depth_precision(*precision, *planes);
    fmt::print("depth-precision chart → {}/index.html\n", precision->out_dir);
    exit_code = kExitOk;
  });

  auto resolution = std::make_shared<experiments::SweepOptions>();
  resolution->out_dir = "chart-resolution";
  CLI::App* resolution_cmd = chart->add_subcommand(
      "resolution",
      "each classic method's mismatch against the exact path at framebuffer sizes 64 to 4096, with the predicted "
      "growth (CPU only)");
  resolution_cmd->add_option("--out", resolution->out_dir, "output folder (CSV, JSON, charts, index.html)")
      ->capture_default_str();
  resolution_cmd->add_flag("--quick", resolution->quick, "sizes 64 to 512 only");
  resolution_cmd->callback([resolution, &exit_code] {
    experiments::run_resolution_sweep(*resolution);
    fmt::print("resolution chart → {}/index.html\n", resolution->out_dir);
    exit_code = kExitOk;
  });

  auto summary = std::make_shared<experiments::SweepOptions>();
  summary->out_dir = "chart-summary";
  auto from = std::make_shared<std::vector<std::string>>();
  CLI::App* summary_cmd = chart->add_subcommand(
      "summary",
      "every measured boundary beside its prediction in one chart, read from earlier runs' JSON (stability.json, "
      "zfight.json, depth_r.json, depth_precision.json, resolution.json)");
  summary_cmd->add_option("--out", summary->out_dir, "output folder (JSON, chart, index.html)")->capture_default_str();
  summary_cmd->add_option("--from", *from,
                          "a folder of an earlier run (repeatable); default: those of sweep-stability, sweep-zfight, "
                          "sweep-polygon-offset, chart-depth-precision, chart-resolution that exist here");
  summary_cmd->callback([summary, from, &exit_code] {
    experiments::run_summary(*summary, *from);
    fmt::print("summary chart → {}/index.html\n", summary->out_dir);
    exit_code = kExitOk;
  });
}

}  // namespace rastercmp::app
