// rastercmp capture [--suite DIR] [--case GLOB] --out ROOT [--device D] [--validate]
// Records every scene of a suite on a Vulkan device, for `compare --capture` and
// `conformance --captures` to judge later, elsewhere (docs/compare.md "Captures"):
// ROOT/<scene path relative to the suite, without .json>/ gets what `render` writes (owner.tif,
// depth_raw.tif, render.json with the device's name, driver and limits), or not_supported.txt
// with the device's message when it refuses the scene. Exit 0 when every scene was recorded or
// refused, 1 when some failed (device loss, out of memory, validation messages, a scene the
// device cannot take), 2 bad input, 3 no Vulkan.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "compare/case_run.hpp"
#include "compare/case_select.hpp"
#include "compare/conformance.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::app {
namespace {
namespace fs = std::filesystem;

struct CaptureArgs {
  std::string suite_dir;
  std::vector<std::string> case_globs;
  std::string out_dir;
  RenderOptions options;
};

// Removes what an earlier capture left that the new one does not replace.
void remove_stale(const std::string& dir, bool not_supported) {
  std::error_code ec;
  if (not_supported) {
    for (const char* name : {"owner.tif", "owner.png", "depth_raw.tif", "depth.exr", "render.json"})
      fs::remove(fs::path(dir) / name, ec);
  } else {
    fs::remove(fs::path(dir) / kCaptureNotSupportedFile, ec);
    fs::remove(fs::path(dir) / "depth_raw.tif", ec);
    fs::remove(fs::path(dir) / "depth.exr", ec);
  }
}

// Records one scene; returns whether it was recorded or refused (not a failure).
bool capture_one(std::unique_ptr<VulkanRenderer>& renderer, const VkOptions& vk, const SuiteCase& c,
                 const std::string& dir) {
  if (!renderer) renderer = std::make_unique<VulkanRenderer>(vk);  // after a device loss
  const size_t messages_before = renderer->validation_messages().size();
  try {
    const RenderResult result = renderer->render(c.scene);
    const auto& messages = renderer->validation_messages();
    if (messages.size() != messages_before) {
      for (size_t i = messages_before; i < messages.size(); ++i) fmt::print(stderr, "validation: {}\n", messages[i]);
      fmt::print("{}: failed: {} validation message(s); not recorded\n", c.name, messages.size() - messages_before);
      return false;
    }
    ensure_output_dir(dir);
    remove_stale(dir, false);
    write_render_outputs(result, dir);
    fmt::print("{}: {}x{}, {} sample(s), depth {} → {}\n", c.name, result.width, result.height, result.samples,
               result.has_depth() ? to_string(result.depth_format) : "none", dir);
    return true;
  } catch (const NotSupportedError& e) {
    ensure_output_dir(dir);
    remove_stale(dir, true);
    write_text_file_atomic((fs::path(dir) / kCaptureNotSupportedFile).string(), std::string(e.what()) + "\n");
    fmt::print("{}: not supported: {} → {}\n", c.name, e.what(), dir);
    return true;
  } catch (const DeviceError& e) {
    fmt::print("{}: failed: device: {}\n", c.name, e.what());
    if (!e.out_of_memory()) renderer.reset();
    return false;
  } catch (const InputError& e) {
    // A scene the device's limits reject (a viewport past its bounds): nothing to record.
    fmt::print("{}: failed: {}\n", c.name, e.what());
    return false;
  }
}

int run_capture(const CaptureArgs& args) {
  const VkOptions vk = make_vk_options(args.options);
  const std::string suite_dir = args.suite_dir.empty() ? default_suite_dir() : args.suite_dir;
  std::vector<SuiteCase> cases = select_cases(load_suite(suite_dir), CaseFilter{{}, args.case_globs, {}}, "");
  if (cases.empty()) throw UsageError(fmt::format("no case of the suite {} matches --case", suite_dir));
  ensure_output_dir(args.out_dir);      // before any work: an unwritable folder is a usage error
  auto renderer = std::make_unique<VulkanRenderer>(vk);  // no device: exit 3 before any file is written
  const OutputLock lock(args.out_dir);  // a conformance or capture writing there: exit 2 naming it
  const DeviceInfo device = renderer->device();
  fmt::print("capture: {} case(s) of {} on {} ({}) → {}\n", cases.size(), suite_dir, device.name, device.driver_info,
             args.out_dir);
  size_t failed = 0;
  for (const SuiteCase& c : cases)
    if (!capture_one(renderer, vk, c, capture_dir_for(args.out_dir, suite_dir, c.path))) ++failed;
  fmt::print("{} case(s) recorded or refused, {} failed\n", cases.size() - failed, failed);
  return failed == 0 ? kExitOk : kExitMismatch;
}

}  // namespace

void add_capture_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CaptureArgs>();
  CLI::App* cmd = app.add_subcommand("capture", "record every scene of a suite on a Vulkan device, to judge later");
  cmd->add_option("--suite", args->suite_dir, "suite folder (every *.json below it); default: the built-in scenes/");
  cmd->add_option("--case", args->case_globs, "record only cases whose name matches this glob (repeatable)");
  cmd->add_option("--out", args->out_dir, "capture root: one folder per scene, as the suite lays them out")->required();
  cmd->add_option("--device", args->options.device, "Vulkan device: name substring or index (default: lavapipe)");
  cmd->add_flag("--validate", args->options.validate, "enable the Vulkan validation layer; a message fails the scene");
  cmd->callback([args, &exit_code] { exit_code = run_capture(*args); });
}

}  // namespace rastercmp::app
