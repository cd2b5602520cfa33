// rastercmp compare SCENE.json... [--profile lavapipe|spec] [--json FILE] [--report DIR]
//                  [--capture DIR]
// Renders each scene on the CPU (expected) and the Vulkan device (actual) and diffs them; with
// --capture, the one scene's actual is the render recorded in DIR (rastercmp capture / render).
// Exit: 0 every scene Pass / QualityWarning / NotSupported, 1 any Fail / ResourceError /
// InternalError, 2 bad input, 3 no Vulkan (docs/compare.md).
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "compare/case_judge.hpp"
#include "compare/case_run.hpp"
#include "compare/conformance.hpp"
#include "compare/explain_text.hpp"
#include "compare/report.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"
#include "model/scene_io.hpp"

namespace rastercmp::app {
namespace {

struct CompareArgs {
  std::vector<std::string> scene_paths;
  std::string json_file;
  std::string report_dir;
  std::string capture_dir;
  RenderOptions options;
};

std::string owner_text(uint32_t owner) {
  if (owner == kOwnerBackground) return "background";
  return fmt::format("draw {} primitive {}", owner_draw(owner), owner_primitive(owner));
}

void print_case(const CaseRecord& record) {
  const std::string method = record.cpu_method == "exact" ? "" : " [CPU method " + record.cpu_method + "]";
  fmt::print("{}: {} ({}){}\n", record.name, to_string(record.verdict), record.message, method);
  if (!record.diff) return;
  // The diff's expected is the CPU render and its actual the device's; a judged CPU method is named
  // from its side (docs/compare.md "Who is judged"): the device is then the reference.
  const bool method_judged = record.cpu_method != "exact";
  for (const BadSample& b : record.diff->first_bad) {
    if (method_judged) {
      const std::string kind = b.kind == "missing" ? "the method adds" : b.kind == "unexpected" ? "the method lacks" : b.kind;
      std::string depth;
      if (b.has_depth)
        depth = fmt::format(", depth device {:#x} method {:#x}", b.actual_depth_raw, b.expected_depth_raw);
      fmt::print("  ({}, {}) sample {}: {}: device {}, method {}{}\n", b.at.x, b.at.y, b.at.sample, kind,
                 owner_text(b.actual_owner), owner_text(b.expected_owner), depth);
      continue;
    }
    std::string depth;
    if (b.has_depth)
      depth = fmt::format(", depth expected {:#x} actual {:#x}", b.expected_depth_raw, b.actual_depth_raw);
    fmt::print("  ({}, {}) sample {}: {}: expected {}, actual {}{}\n", b.at.x, b.at.y, b.at.sample, b.kind,
               owner_text(b.expected_owner), owner_text(b.actual_owner), depth);
  }
}

std::string compare_json(const RunInfo& info, const std::vector<CaseRecord>& records) {
  nlohmann::ordered_json j;
  j["profile"] = info.profile;
  if (!info.profile_warning.empty()) j["profile_warning"] = info.profile_warning;
  j["device"] = info.device;
  j["driver"] = info.driver;
  j["fma"] = info.fma;
  nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
  for (const CaseRecord& record : records) scenes.push_back(case_to_json(record, false));
  j["scenes"] = scenes;
  return j.dump(2) + "\n";
}

// The capture's device; a render.json that cannot be read is the case's ResourceError (run_capture
// names the file), so the run goes on with a device known only by its folder.
DeviceInfo device_of_capture(const std::string& dir) {
  try {
    return capture_device(dir);
  } catch (const InputError&) {
    DeviceInfo unknown;
    unknown.name = "unknown device (capture " + dir + ")";
    return unknown;
  }
}

int run_compare(const CompareArgs& args) {
  const CompareProfile profile = args.options.profile == "spec" ? CompareProfile::Spec : CompareProfile::Lavapipe;
  make_cpu_options(args.options);                          // a bad --method is a usage error before any work
  std::optional<OutputFolder> json_folder, report_folder;  // checked before any work
  if (!args.json_file.empty()) json_folder.emplace(output_file_folder(args.json_file));
  if (!args.report_dir.empty()) report_folder.emplace(args.report_dir);
  std::vector<SuiteCase> cases;
  for (const std::string& path : args.scene_paths) {
    Scene scene = load_checked_scene(path);
    std::string name = scene.name;
    cases.push_back({std::move(name), path, std::move(scene)});
  }

  const bool from_capture = !args.capture_dir.empty();
  if (from_capture && cases.size() != 1) throw UsageError("--capture: expected exactly one scene");
  if (from_capture && !args.options.device.empty())
    throw UsageError("--capture: the device is the capture's, not --device");
  const CpuOptionsForScene cpu_options = [&](const Scene& s) { return make_cpu_options(args.options, &s); };
  const std::unique_ptr<CaseRunner> runner_ptr =
      from_capture ? std::make_unique<CaseRunner>(profile, cpu_options, device_of_capture(args.capture_dir))
                   : std::make_unique<CaseRunner>(profile, cpu_options, make_vk_options(args.options));
  CaseRunner& runner = *runner_ptr;
  RunInfo info = run_info_for(runner);
  info.complete = true;  // the report is written once every scene is compared
  fmt::print("{} ({}): {} profile\n", info.device, info.driver, info.profile);
  if (!info.profile_warning.empty()) fmt::print(stderr, "warning: {}\n", info.profile_warning);
  std::vector<CaseRecord> records;
  for (const SuiteCase& c : cases) {
    const CaseResult result = from_capture ? runner.run_capture(c.scene, args.capture_dir) : runner.run(c.scene);
    CaseRecord record = make_case_record(c, result, Expectations{});
    if (!args.report_dir.empty()) {
      record.images = write_case_images(args.report_dir, c.name, result);
      record.explains =
          write_case_explanations(args.report_dir, c.name, c.scene, runner.cpu_options(c.scene), result, profile);
    }
    print_case(record);
    records.push_back(std::move(record));
  }
  if (!args.json_file.empty()) write_text_file_atomic(args.json_file, compare_json(info, records));
  if (json_folder) json_folder->keep();
  if (report_folder) report_folder->keep();
  if (!args.report_dir.empty()) {
    write_report_html(args.report_dir, info, records);
    fmt::print("report: {}\n", (std::filesystem::path(args.report_dir) / "index.html").string());
  }
  const bool any_failure =
      std::any_of(records.begin(), records.end(), [](const CaseRecord& r) { return is_failure(r.verdict); });
  return any_failure ? kExitMismatch : kExitOk;
}

}  // namespace

void add_compare_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "render scenes on the CPU and the Vulkan device and diff them");
  cmd->add_option("scenes", args->scene_paths, "scene files (JSON)")->required();
  cmd->add_option("--json", args->json_file, "write per-scene results as JSON to this file");
  cmd->add_option("--report", args->report_dir, "write an HTML report (index.html and images) into this folder");
  cmd->add_option("--capture", args->capture_dir,
                  "judge the render recorded in this folder (rastercmp capture / render) instead of rendering");
  add_render_options(*cmd, args->options);
  cmd->callback([args, &exit_code] { exit_code = run_compare(*args); });
}

}  // namespace rastercmp::app
