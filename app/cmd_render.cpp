// rastercmp render SCENE.json --backend cpu|vulkan --out DIR
#include <memory>
#include <string>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"
#include "model/scene_io.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::app {
namespace {

struct RenderArgs {
  std::string scene_path;
  std::string backend = "cpu";
  std::string out_dir;
  RenderOptions options;
};

int run_render(const RenderArgs& args) {
  const Scene scene = load_checked_scene(args.scene_path);
  CpuOptions cpu_options = make_cpu_options(args.options, &scene);  // a bad --method fails here
  OutputFolder out(args.out_dir);  // before any work: an unwritable folder is a usage error
  RenderResult result;
  if (args.backend == "cpu") {
    pick_installed_lavapipe_release(cpu_options);
    result = render_cpu(scene, cpu_options);
  } else {
    VulkanRenderer renderer(make_vk_options(args.options));
    result = renderer.render(scene);
    for (const std::string& message : renderer.validation_messages()) fmt::print(stderr, "validation: {}\n", message);
    if (!renderer.validation_messages().empty()) {
      fmt::print(stderr, "error: {} validation message(s); the outputs were not written\n",
                 renderer.validation_messages().size());
      return kExitInternal;
    }
  }
  write_render_outputs(result, args.out_dir);
  out.keep();
  fmt::print("{}: {}x{}, {} sample(s), depth {} → {} ({})\n", scene.name, result.width, result.height, result.samples,
             to_string(result.depth_format), args.out_dir, result.device);
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "render one scene and write owner/depth images");
  cmd->add_option("scene", args->scene_path, "scene file (JSON)")->required();
  cmd->add_option("--backend", args->backend, "cpu or vulkan")->check(CLI::IsMember({"cpu", "vulkan"}));
  cmd->add_option("--out", args->out_dir, "output folder")->required();
  add_render_options(*cmd, args->options);
  cmd->callback([args, &exit_code] { exit_code = run_render(*args); });
}

}  // namespace rastercmp::app
