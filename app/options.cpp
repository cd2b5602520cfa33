#include "app/options.hpp"

#include "model/errors.hpp"
#include "model/host.hpp"

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
  cmd.add_option("--profile", o.profile, "CPU profile: lavapipe (bit-exact) or spec (must/may/must-not)")
      ->check(CLI::IsMember({"lavapipe", "spec"}));
  cmd.add_option("--fma", o.fma, "CPU fused multiply-add: auto (as lavapipe on this host), on, off")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  cmd.add_option("--method", o.methods, method_option_help());
  cmd.add_option("--threads", o.threads, "CPU threads: 0 = exact scalar path, N >= 1 = fast path");
  cmd.add_option("--device", o.device, "Vulkan device: name substring or index (default: lavapipe)");
  cmd.add_flag("--validate", o.validate, "enable the Khronos validation layer");
}

CpuOptions make_cpu_options(const RenderOptions& o, const Scene* scene) {
  CpuOptions cpu;
  cpu.profile = o.profile == "spec" ? CpuProfile::Spec : CpuProfile::Lavapipe;
  cpu.fma = o.fma == "auto" ? lavapipe_fuses_on_this_host() : o.fma == "on";
  cpu.threads = o.threads;
  if (scene) cpu.methods = scene->methods;
  for (const std::string& m : o.methods) {
    const auto eq = m.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == m.size())
      throw UsageError("--method " + m + ": expected STAGE=NAME, e.g. --method fill=scanline");
    MethodChoice choice{m.substr(0, eq), m.substr(eq + 1)};
    cpu::classic::check_method_choice(choice);  // an unknown stage or name: UsageError listing the known ones
    // The command line wins over the scene's "methods" for the same stage.
    std::erase_if(cpu.methods, [&](const MethodChoice& c) { return c.stage == choice.stage; });
    cpu.methods.push_back(choice);
  }
  return cpu;
}

VkOptions make_vk_options(const RenderOptions& o) { return VkOptions{o.device, o.validate}; }

}  // namespace rastercmp::app
