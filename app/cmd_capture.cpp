// rastercmp capture [--suite DIR] [--case GLOB] --out ROOT [--device D] [--validate]
// Records every scene of a suite on a Vulkan device, for `compare --capture` and
// `conformance --captures` to judge later, elsewhere (docs/compare.md "Captures"):
// ROOT/<scene path relative to the suite, without .json; a model file keeps its extension>/ gets
// what `render` writes (owner.tif, depth_raw.tif, render.json with the device's name, driver and
// limits), or not_supported.txt with the device's message when it refuses the scene. Exit 0 when every scene was recorded or
// refused, 1 when some failed (device loss, out of memory, validation messages, a scene the
// device cannot take), 2 bad input or a file it cannot write (a full disk: each scene's folder is
// written whole or left as it was), 3 no Vulkan.
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
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

// A scene's capture appears whole or not at all: its files are written into a sibling temporary
// folder ".LEAF.tmpPID" and swapped in (renameat2 RENAME_EXCHANGE, or two renames where the file
// system cannot exchange), so a full disk or a kill leaves the earlier capture or none, never a
// new image beside an old render.json. A temporary folder a killed capture left is removed first.
void write_capture_folder(const std::string& dir, const std::function<void(const std::string&)>& write) {
  const fs::path final_dir = fs::path(dir).lexically_normal();
  const fs::path parent = final_dir.parent_path();
  const std::string leaf = final_dir.filename().string();
  ensure_output_dir(parent.string());
  std::error_code ec;
  const std::string stale_prefix = "." + leaf + ".tmp";
  for (auto it = fs::directory_iterator(parent, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::string pid = name.rfind(stale_prefix, 0) == 0 ? name.substr(stale_prefix.size()) : "";
    if (!pid.empty() && pid.size() <= 10 && pid.find_first_not_of("0123456789") == std::string::npos &&
        writer_gone(std::stoll(pid))) {
      std::error_code removed;
      fs::remove_all(it->path(), removed);
    }
  }
  const fs::path temp = parent / fmt::format("{}{}", stale_prefix, getpid());
  fs::remove_all(temp, ec);
  try {
    write(temp.string());
  } catch (...) {
    fs::remove_all(temp, ec);
    throw;
  }
  if (!fs::exists(final_dir, ec)) {
    fs::rename(temp, final_dir);
    return;
  }
  if (renameat2(AT_FDCWD, temp.c_str(), AT_FDCWD, final_dir.c_str(), RENAME_EXCHANGE) != 0) {
    const fs::path earlier = parent / fmt::format(".{}.old{}", leaf, getpid());
    fs::rename(final_dir, earlier);
    fs::rename(temp, final_dir);
    fs::remove_all(earlier, ec);
    return;
  }
  fs::remove_all(temp, ec);  // the earlier capture, exchanged into the temporary name
}

// Records one scene; returns whether it was recorded or refused (not a failure). A file it cannot
// write (a full disk) ends the capture: exit 2 naming it, the scene's folder as it was before.
bool capture_one(std::unique_ptr<VulkanRenderer>& renderer, const VkOptions& vk, const SuiteCase& c,
                 const std::string& dir) {
  if (!renderer) renderer = std::make_unique<VulkanRenderer>(vk);  // after a device loss
  const size_t messages_before = renderer->validation_messages().size();
  std::optional<RenderResult> result;
  std::string refusal;
  try {
    result = renderer->render(c.scene);
  } catch (const NotSupportedError& e) {
    refusal = e.what();
  } catch (const DeviceError& e) {
    fmt::print("{}: failed: device: {}\n", c.name, e.what());
    if (!e.out_of_memory()) renderer.reset();
    return false;
  } catch (const InputError& e) {
    // A scene the device's limits reject (a viewport past its bounds): nothing to record.
    fmt::print("{}: failed: {}\n", c.name, e.what());
    return false;
  }
  if (result) {
    const auto& messages = renderer->validation_messages();
    if (messages.size() != messages_before) {
      for (size_t i = messages_before; i < messages.size(); ++i) fmt::print(stderr, "validation: {}\n", messages[i]);
      fmt::print("{}: failed: {} validation message(s); not recorded\n", c.name, messages.size() - messages_before);
      return false;
    }
    write_capture_folder(dir, [&](const std::string& temp) { write_render_outputs(*result, temp); });
    fmt::print("{}: {}x{}, {} sample(s), depth {} → {}\n", c.name, result->width, result->height, result->samples,
               result->has_depth() ? to_string(result->depth_format) : "none", dir);
    return true;
  }
  write_capture_folder(dir, [&](const std::string& temp) {
    ensure_output_dir(temp);
    write_text_file_atomic((fs::path(temp) / kCaptureNotSupportedFile).string(), refusal + "\n");
  });
  fmt::print("{}: not supported: {} → {}\n", c.name, refusal, dir);
  return true;
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
