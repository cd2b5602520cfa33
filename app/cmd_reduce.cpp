// rastercmp reduce SCENE [--out FILE] [--max-runs N]
// Shrinks a failing scene to a small one that still fails the same way (docs/soak.md "Reduction").
// Exit: 0 reduced scene written, 2 bad input (including a scene that does not fail), 3 no Vulkan.
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "compare/case_run.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"
#include "model/scene_io.hpp"
#include "soak/judge.hpp"
#include "soak/primitives.hpp"
#include "soak/reduce.hpp"
#include "soak/scene_write.hpp"

namespace rastercmp::app {
namespace {

struct ReduceArgs {
  std::string scene_path;
  std::string out_file;
  size_t max_runs = 3000;
  RenderOptions options;
};

std::string default_out(const std::string& scene_path) {
  std::filesystem::path p(scene_path);
  return (p.parent_path() / (p.stem().string() + ".reduced.json")).string();
}

int run_reduce(const ReduceArgs& args) {
  const CompareProfile profile = args.options.profile == "spec" ? CompareProfile::Spec : CompareProfile::Lavapipe;
  make_cpu_options(args.options);
  const Scene scene = load_checked_scene(args.scene_path);
  const std::string out = args.out_file.empty() ? default_out(args.scene_path) : args.out_file;
  OutputFolder out_folder(output_file_folder(out));  // a folder in its place or an unwritable one: exit 2 now
  CaseRunner runner(
      profile, [&](const Scene& s) { return make_cpu_options(args.options, &s); }, make_vk_options(args.options));
  const std::string kind = soak::failure_kind(soak::judge(runner, scene));
  if (kind.empty())
    throw UsageError(
        fmt::format("{}: the scene does not fail on {}: nothing to reduce", args.scene_path, runner.device().name));
  soak::ReduceStats stats;
  Scene reduced = soak::reduce_scene(
      scene, [&](const Scene& s) { return soak::failure_kind(soak::judge(runner, s)) == kind; }, args.max_runs, &stats);
  reduced.description = fmt::format("{}{}reduced by rastercmp reduce ({} failure)", scene.description,
                                    scene.description.empty() ? "" : "; ", kind);
  soak::write_scene_file(out, reduced);
  out_folder.keep();
  fmt::print("{}: {} failure; {} draws, {} primitives -> {} draws, {} primitives in {} runs{}\n", args.scene_path, kind,
             stats.draws_before, stats.primitives_before, stats.draws_after, stats.primitives_after, stats.runs,
             stats.hit_limit ? " (run limit reached)" : "");
  fmt::print("reduced scene: {}\n", out);
  return kExitOk;
}

}  // namespace

void add_reduce_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ReduceArgs>();
  CLI::App* cmd = app.add_subcommand("reduce", "shrink a failing scene to a small one that fails the same way");
  cmd->add_option("scene", args->scene_path, "failing scene file (JSON)")->required();
  cmd->add_option("--out", args->out_file, "reduced scene file (default: SCENE's name with .reduced.json)");
  cmd->add_option("--max-runs", args->max_runs, "at most this many comparisons (default 3000)")
      ->check(CLI::Range(size_t(1), size_t(1) << 30));
  add_render_options(*cmd, args->options);
  cmd->callback([args, &exit_code] { exit_code = run_reduce(*args); });
}

}  // namespace rastercmp::app
