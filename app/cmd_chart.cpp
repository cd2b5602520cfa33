// rastercmp chart speed-accuracy [--out DIR] [--quick] [--reps N] [--clock cpu|wall]
// rastercmp chart scene-needs [--out DIR] [--quick]
#include <memory>
#include <string>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "compare/case_select.hpp"
#include "experiments/skip_savings.hpp"
#include "experiments/speed_accuracy.hpp"
#include "model/errors.hpp"

namespace rastercmp::app {

void add_chart_command(CLI::App& app, int& exit_code) {
  CLI::App* chart = app.add_subcommand("chart", "measured charts: speed-accuracy, scene-needs");
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
    experiments::run_scene_needs(*needs, suite);
    fmt::print("scene-needs chart → {}/index.html\n", needs->out_dir);
    exit_code = kExitOk;
  });
}

}  // namespace rastercmp::app
