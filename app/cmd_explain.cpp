// rastercmp explain SCENE.json --pixel X,Y [--sample S] [--capture DIR]: the sample's history on
// the CPU path (cpu_raster/explain.hpp, RenderDoc pixel-history style), the Vulkan value there (or
// the one recorded in DIR, as compare --capture judges it) and a one-line classification; with
// --profile spec also the sample's owner alternatives (docs/compare.md, explain). Exit 0 when the
// sample matches (or differs only on a spec profile May sample or by an allowed owner), 1 when its
// owner or raw depth differs, 2 bad input (an unusable capture included), 3 no Vulkan.
#include <fmt/core.h>

#include <charconv>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "compare/case_run.hpp"
#include "compare/depth_units.hpp"
#include "compare/diff.hpp"
#include "compare/explain_text.hpp"
#include "model/errors.hpp"
#include "model/scene_io.hpp"

namespace rastercmp::app {
namespace {

struct ExplainArgs {
  std::string scene_path;
  std::string pixel;
  uint32_t sample = 0;
  std::string capture_dir;
  RenderOptions options;
};

// The CPU options used and both renders of the scene.
struct Renders {
  CpuOptions cpu;
  RenderResult expected, actual;
};

Renders render_on_device(const Scene& scene, const RenderOptions& options) {
  Renders r{make_cpu_options(options, &scene), {}, {}};
  VulkanRenderer vulkan(make_vk_options(options));
  if (vulkan.device().sub_pixel_precision_bits != 0) {
    r.cpu.sub_pixel_bits = vulkan.device().sub_pixel_precision_bits;
    r.cpu.viewport_sub_pixel_bits = vulkan.device().limits.viewport_sub_pixel_bits;
  }
  pick_lavapipe_release(r.cpu, vulkan.device().driver_info);
  r.expected = render_cpu(scene, r.cpu);
  r.actual = vulkan.render(scene);
  for (const std::string& message : vulkan.validation_messages()) fmt::print(stderr, "validation: {}\n", message);
  return r;
}

// The render recorded in `dir`, read and checked against the scene as compare --capture does
// (CaseRunner::run_capture: the capture's limits set the CPU options). A capture that cannot be
// judged is bad input.
Renders read_capture(const Scene& scene, const RenderOptions& options, CompareProfile profile, const std::string& dir) {
  if (!options.device.empty()) throw UsageError("--capture: the device is the capture's, not --device");
  CaseRunner runner(
      profile, [&options](const Scene& s) { return make_cpu_options(options, &s); }, capture_device(dir));
  CaseResult result = runner.run_capture(scene, dir);
  if (!result.expected || !result.actual) throw UsageError(result.message);  // "capture: FILE: what is wrong"
  return {runner.cpu_options(scene), std::move(*result.expected), std::move(*result.actual)};
}

uint32_t parse_coordinate(std::string_view text, const std::string& whole) {
  uint32_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size())
    throw UsageError("--pixel " + whole + ": expected X,Y with non-negative integers, e.g. --pixel 12,7");
  return value;
}

void check_sample_in_scene(const Scene& scene, uint32_t x, uint32_t y, uint32_t sample) {
  if (x >= scene.width || y >= scene.height)
    throw UsageError(
        fmt::format("--pixel {},{}: outside the {}x{} framebuffer of {}", x, y, scene.width, scene.height, scene.name));
  if (sample >= scene.samples)
    throw UsageError(fmt::format("--sample {}: the scene has {} sample(s) per pixel", sample, scene.samples));
}

int run_explain(const ExplainArgs& args) {
  const auto comma = args.pixel.find(',');
  if (comma == std::string::npos) throw UsageError("--pixel " + args.pixel + ": expected X,Y, e.g. --pixel 12,7");
  const std::string_view pixel(args.pixel);
  const uint32_t x = parse_coordinate(pixel.substr(0, comma), args.pixel);
  const uint32_t y = parse_coordinate(pixel.substr(comma + 1), args.pixel);
  const Scene scene = load_checked_scene(args.scene_path);
  check_sample_in_scene(scene, x, y, args.sample);

  const CompareProfile profile = args.options.profile == "spec" ? CompareProfile::Spec : CompareProfile::Lavapipe;
  const Renders renders = args.capture_dir.empty() ? render_on_device(scene, args.options)
                                                   : read_capture(scene, args.options, profile, args.capture_dir);
  const RenderResult& expected = renders.expected;
  const RenderResult& actual = renders.actual;

  fmt::print("{}", explain_sample_text(scene, renders.cpu, expected, actual, profile, x, y, args.sample));
  const size_t i = expected.index(x, y, args.sample);
  const SampleClass c = classify_sample(expected, actual, profile, i);
  const bool depth_differs =
      expected.has_depth() && actual.has_depth() && expected.owner[i] == actual.owner[i] &&
      depth_diff_raw_units(expected.depth_format, expected.depth_raw[i], actual.depth_raw[i]) != 0;
  const bool differs =
      c == SampleClass::Missing || c == SampleClass::Unexpected || c == SampleClass::WrongOwner || depth_differs;
  return differs ? kExitMismatch : kExitOk;
}

}  // namespace

void add_explain_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ExplainArgs>();
  CLI::App* cmd = app.add_subcommand("explain", "show why one pixel (sample) came out as it did on both backends");
  cmd->add_option("scene", args->scene_path, "scene file (JSON)")->required();
  cmd->add_option("--pixel", args->pixel, "pixel X,Y (0,0 is the top-left pixel)")->required();
  cmd->add_option("--sample", args->sample, "sample index for multisampled scenes (default 0)");
  cmd->add_option("--capture", args->capture_dir,
                  "explain the render recorded in this folder (rastercmp capture / render) instead of rendering");
  add_render_options(*cmd, args->options);
  cmd->callback([args, &exit_code] { exit_code = run_explain(*args); });
}

}  // namespace rastercmp::app
