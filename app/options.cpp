#include "app/options.hpp"

#include <fmt/core.h>

#include <filesystem>

#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/image_io.hpp"
#include "model/mesh_import.hpp"
#include "model/scene_io.hpp"

namespace rastercmp::app {
namespace {

// --help's text for --method: every stage with its names, from the registry.
std::string method_option_help() {
  std::string text = "classic method for a stage, STAGE=NAME (repeatable; `rastercmp methods` describes each):";
  for (const cpu::classic::StageInfo& s : cpu::classic::method_stages())
    text += "\n  " + std::string(s.stage) + "=" + cpu::classic::method_names(s.stage);
  return text;
}

}  // namespace

void add_render_options(CLI::App& cmd, RenderOptions& o) {
  std::vector<std::string> profiles = {"lavapipe", "spec"};
  std::string releases;
  for (const LavapipeRelease& r : lavapipe_releases()) {
    profiles.push_back(r.profile);
    releases += std::string(releases.empty() ? "" : ", ") + r.profile;
  }
  cmd.add_option("--profile", o.profile,
                 "CPU profile: lavapipe (bit-exact, the modelled release the driver is), " + releases +
                     " (bit-exact, that release), or spec (must/may/must-not)")
      ->check(CLI::IsMember(profiles));
  cmd.add_option("--fma", o.fma, "CPU fused multiply-add: auto (as lavapipe on this host), on, off")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  cmd.add_option("--method", o.methods, method_option_help());
  cmd.add_option("--threads", o.threads, "CPU threads: 0 = exact scalar path, N >= 1 = fast path (at most 256)")
      ->check(CLI::Range(0u, kMaxCpuThreads));
  cmd.add_option("--device", o.device, "Vulkan device: name substring or index (default: lavapipe)");
  cmd.add_flag("--validate", o.validate, "enable the Khronos validation layer");
}

CpuOptions make_cpu_options(const RenderOptions& o, const Scene* scene) {
  CpuOptions cpu;
  cpu.profile = o.profile == "spec" ? CpuProfile::Spec : CpuProfile::Lavapipe;
  if (const LavapipeRelease* forced = find_lavapipe_release(o.profile)) {
    cpu.lavapipe = forced;
    cpu.lavapipe_from_driver = false;
  } else {
    cpu.lavapipe = &default_lavapipe_release();  // until the driver compared with says which
  }
  cpu.fma = o.fma == "auto" ? lavapipe_fuses_on_this_host() : o.fma == "on";
  cpu.threads = o.threads;
  if (scene) cpu.methods = scene->methods;
  for (const std::string& m : o.methods) {
    constexpr size_t kMaxShown = 64;  // no known STAGE=NAME is this long; a longer one is not echoed whole
    if (m.size() > kMaxShown)
      throw UsageError("--method " + m.substr(0, kMaxShown) + "... (" + std::to_string(m.size()) +
                       " bytes): expected STAGE=NAME, e.g. --method fill=scanline");
    const auto eq = m.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == m.size())
      throw UsageError("--method " + m + ": expected STAGE=NAME, e.g. --method fill=scanline");
    MethodChoice choice{m.substr(0, eq), m.substr(eq + 1)};
    if (const std::string problem = method_choice_problem(choice); !problem.empty()) throw UsageError("--" + problem);
    // The command line wins over the scene's "methods" for the same stage.
    std::erase_if(cpu.methods, [&](const MethodChoice& c) { return c.stage == choice.stage; });
    cpu.methods.push_back(choice);
  }
  return cpu;
}

void check_scene_methods(const Scene& scene, const std::string& path) {
  for (const MethodChoice& choice : scene.methods) {
    if (const std::string problem = method_choice_problem(choice); !problem.empty())
      throw InputError(path, "$.methods." + choice.stage,
                       "expected a stage and method the CPU renderer knows: " + problem);
  }
}

OutputFolder::OutputFolder(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (fs::path p = fs::path(dir).lexically_normal(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    created_.push_back(p.string());
    if (p == p.parent_path()) break;
  }
  try {
    ensure_output_dir(dir);  // InputError: exit 2 before any work
  } catch (...) {
    remove_empty_created();
    throw;
  }
}

OutputFolder::~OutputFolder() { remove_empty_created(); }

void OutputFolder::remove_empty_created() {
  std::error_code ec;
  for (const std::string& dir : created_) {
    if (!std::filesystem::is_empty(dir, ec) || ec) return;
    std::filesystem::remove(dir, ec);
  }
}

std::string output_file_folder(const std::string& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(file, "", "expected a file to write, not a folder or other special file");
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  return parent.empty() ? "." : parent.string();
}

Scene load_checked_scene(const std::string& path) {
  Scene scene = load_scene_or_model(path);
  check_scene_methods(scene, path);
  return scene;
}

VkOptions make_vk_options(const RenderOptions& o) { return VkOptions{o.device, o.validate}; }

void pick_lavapipe_release(CpuOptions& cpu, const std::string& driver_info) {
  if (!cpu.lavapipe_from_driver) return;
  const LavapipeReleaseChoice choice = lavapipe_release_for_driver(driver_info);
  cpu.lavapipe = choice.release;
  if (!choice.warning.empty()) fmt::print(stderr, "warning: {}\n", choice.warning);
}

void pick_installed_lavapipe_release(CpuOptions& cpu) {
  if (!cpu.lavapipe_from_driver || cpu.profile != CpuProfile::Lavapipe) return;
  try {
    for (const DeviceInfo& device : list_vulkan_devices())
      if (device.is_lavapipe) return pick_lavapipe_release(cpu, device.driver_info);
  } catch (const EnvironmentError&) {
  }
  cpu.lavapipe = &default_lavapipe_release();
  fmt::print(stderr,
             "warning: no lavapipe driver found to pick the release from: rendering as {} (--profile {} "
             "names one)\n",
             cpu.lavapipe->profile, cpu.lavapipe->profile);
}

}  // namespace rastercmp::app
