// rastercmp soak --seed S --count N [--family F]... [--out DIR] [--no-reduce] [--every-worker]
// Random scenes from the scene format's corner cases, compared against the Vulkan device until N
// primitives have run; each failure is reduced and written to DIR (docs/soak.md).
// Exit: 0 no failure, 1 failures found, 2 bad input, 3 no Vulkan.
#include <fmt/core.h>
#include <charconv>

#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "compare/case_run.hpp"
#include "model/errors.hpp"
#include "soak/soak.hpp"

namespace rastercmp::app {
namespace {

struct SoakArgs {
  soak::SoakOptions soak;
  bool no_reduce = false;
  bool every_worker = false;
  RenderOptions options;
};

int run_soak_command(SoakArgs& args) {
  args.soak.reduce = !args.no_reduce;
  const CompareProfile profile = args.options.profile == "spec" ? CompareProfile::Spec : CompareProfile::Lavapipe;
  make_cpu_options(args.options);  // a bad --method is a usage error before any work
  if (args.every_worker && args.options.threads < 2)
    throw UsageError(fmt::format("--every-worker: needs --threads 2 or more (the fast path's workers), got {}",
                                 args.options.threads));
  for (const std::string& f : args.soak.families)
    if (!soak::is_family(f)) {
      std::string all;
      for (const std::string& n : soak::family_names()) all += (all.empty() ? "" : ", ") + n;
      throw UsageError(fmt::format("--family {}: unknown family (families: {})", f, all));
    }
  const auto cpu_options = [&](const Scene& s) {
    CpuOptions cpu = make_cpu_options(args.options, &s);
    cpu.every_worker = args.every_worker;
    return cpu;
  };
  CaseRunner runner(profile, cpu_options, make_vk_options(args.options));
  fmt::print("soak: seed {}, {} primitives, device {} ({}), {} profile\n", args.soak.seed, args.soak.primitives,
             runner.device().name, runner.device().driver_info, runner.profile_name());
  if (const std::string warning = runner.lavapipe_choice().warning;
      !warning.empty() && profile == CompareProfile::Lavapipe && runner.cpu_options(Scene{}).lavapipe_from_driver)
    fmt::print(stderr, "warning: {}\n", warning);
  const soak::SoakSummary summary = soak::run_soak(runner, args.soak, [](const soak::SoakFailure& f) {
    fmt::print("FAIL {} ({}): {} primitives", f.name, f.kind, f.primitives);
    if (f.reduce_runs > 0) fmt::print(" reduced to {} in {} runs", f.reduced_primitives, f.reduce_runs);
    if (!f.reduced_path.empty()) fmt::print(" -> {}", f.reduced_path);
    fmt::print("\n");
    std::fflush(stdout);
  });
  fmt::print("{}", soak::format_summary(summary));
  return summary.failures.empty() ? kExitOk : kExitMismatch;
}

}  // namespace

void add_soak_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SoakArgs>();
  CLI::App* cmd = app.add_subcommand("soak", "random differential soak: generated scenes against the Vulkan device");
  // Checked before CLI11 converts it, which saturates a value past 2^64 - 1 instead of refusing it.
  const CLI::Validator uint64_text(
      [](std::string& text) {
        uint64_t value = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (!text.empty() && ec == std::errc() && end == text.data() + text.size()) return std::string();
        return "expected an integer from 0 to 18446744073709551615, found " + text;
      },
      "UINT64");
  cmd->add_option("--seed", args->soak.seed, "random seed (same seed, same scenes)")->check(uint64_text);
  cmd->add_option("--count", args->soak.primitives, "primitives to run (scenes are generated until this many ran)")
      ->required()
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
  cmd->add_option("--family", args->soak.families, "only this family (repeatable); default: all");
  cmd->add_option("--out", args->soak.out_dir, "write every failing scene (original and reduced) into this folder");
  cmd->add_flag("--no-reduce", args->no_reduce, "write failing scenes without reducing them");
  cmd->add_flag("--every-worker", args->every_worker,
                "fast path: all --threads workers even on the small scenes one worker would take alone");
  add_render_options(*cmd, args->options);
  cmd->callback([args, &exit_code] { exit_code = run_soak_command(*args); });
}

}  // namespace rastercmp::app
