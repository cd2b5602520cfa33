// rastercmp sweep polygon-offset|stability|zfight [--model M] [--out DIR] [--quick] [--resume]
#include <memory>
#include <string>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "experiments/polygon_offset.hpp"
#include "experiments/model_zfight.hpp"
#include "experiments/stability.hpp"
#include "model/errors.hpp"

namespace rastercmp::app {
namespace {

void add_sweep_options(CLI::App& cmd, experiments::SweepOptions& options, const std::string& default_out) {
  options.out_dir = default_out;
  cmd.add_option("--out", options.out_dir, "output folder (CSV, JSON, charts, index.html)")->capture_default_str();
  cmd.add_flag("--quick", options.quick, "a small grid (seconds), as the tests run it");
  cmd.add_flag("--resume", options.resume, "keep the points already in the folder's CSV and compute the rest");
}

}  // namespace

void add_sweep_command(CLI::App& app, int& exit_code) {
  CLI::App* sweep = app.add_subcommand("sweep", "long parameter sweeps: polygon-offset, stability, zfight");
  sweep->require_subcommand(1);

  auto offset = std::make_shared<experiments::SweepOptions>();
  CLI::App* offset_cmd = sweep->add_subcommand(
      "polygon-offset", "z-fighting against depth-bias factors, clamp, depth format, far/near and viewing angle");
  add_sweep_options(*offset_cmd, *offset, "sweep-polygon-offset");
  offset_cmd->callback([offset, &exit_code] {
    experiments::run_polygon_offset_sweep(*offset);
    fmt::print("polygon-offset sweep → {}/index.html\n", offset->out_dir);
    exit_code = kExitOk;
  });

  auto stability = std::make_shared<experiments::SweepOptions>();
  CLI::App* stability_cmd = sweep->add_subcommand(
      "stability", "where methods stop being right: fight onset, slivers, distance, w near 0, NaN/Inf");
  add_sweep_options(*stability_cmd, *stability, "sweep-stability");
  stability_cmd->callback([stability, &exit_code] {
    experiments::run_stability_sweep(*stability);
    fmt::print("stability sweep → {}/index.html\n", stability->out_dir);
    exit_code = kExitOk;
  });

  auto zfight = std::make_shared<experiments::ModelZfightOptions>();
  CLI::App* zfight_cmd = sweep->add_subcommand(
      "zfight", "z-fighting on a model: owners that move against far/near, per depth format, standard and reversed Z");
  add_sweep_options(*zfight_cmd, zfight->sweep, "sweep-zfight");
  zfight_cmd->add_option("--model", zfight->model, "model file (a format rastercmp import reads)")
      ->required();
  zfight_cmd->callback([zfight, &exit_code] {
    experiments::run_model_zfight_sweep(*zfight);
    fmt::print("zfight sweep → {}/index.html\n", zfight->sweep.out_dir);
    exit_code = kExitOk;
  });
}

}  // namespace rastercmp::app
