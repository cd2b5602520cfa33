// rastercmp chart speed-accuracy [--out DIR] [--quick]
#include <memory>
#include <string>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "experiments/speed_accuracy.hpp"
#include "model/errors.hpp"

namespace rastercmp::app {

void add_chart_command(CLI::App& app, int& exit_code) {
  CLI::App* chart = app.add_subcommand("chart", "measured charts: speed-accuracy");
  chart->require_subcommand(1);
  auto options = std::make_shared<experiments::SweepOptions>();
  options->out_dir = "chart-speed-accuracy";
  CLI::App* cmd = chart->add_subcommand(
      "speed-accuracy", "time per frame against mismatch with lavapipe for every CPU method, Pareto front marked");
  cmd->add_option("--out", options->out_dir, "output folder (CSV, JSON, charts, index.html)")->capture_default_str();
  cmd->add_flag("--quick", options->quick, "fewer repetitions (seconds), as the tests run it");
  cmd->callback([options, &exit_code] {
    experiments::run_speed_accuracy(*options);
    fmt::print("speed-accuracy chart → {}/index.html\n", options->out_dir);
    exit_code = kExitOk;
  });
}

}  // namespace rastercmp::app
