// rastercmp conformance [--suite DIR] [--caselist FILE] [--case GLOB] [--baseline FILE]
//   [--flakes FILE] [--skips FILE] [--shard I/N] [--out DIR] [--profile ...] [--device ...]
//   [--validate] [--threads N] [--captures ROOT]
// Runs a suite through compare (compare/conformance.hpp). SIGINT finishes the current case,
// writes every output and exits 130 with the command to resume.
#include <fmt/core.h>

#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "compare/conformance.hpp"
#include "model/errors.hpp"

namespace rastercmp::app {
namespace {

// Set by the SIGINT handler, polled between cases (a lock-free atomic is signal-safe).
std::atomic<bool> g_stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void request_stop(int) { g_stop_requested.store(true); }

// Installs the SIGINT handler for the lifetime of the run.
class StopOnSigint {
 public:
  StopOnSigint() {
    g_stop_requested.store(false);
    struct sigaction action {};
    action.sa_handler = request_stop;
    action.sa_flags = SA_RESTART;  // a wait inside the driver goes on; the flag is read between cases
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &previous_);
  }
  ~StopOnSigint() { sigaction(SIGINT, &previous_, nullptr); }
  StopOnSigint(const StopOnSigint&) = delete;
  StopOnSigint& operator=(const StopOnSigint&) = delete;

 private:
  struct sigaction previous_ {};
};

struct ConformanceArgs {
  ConformanceOptions conformance;
  std::string shard;
  RenderOptions options;
};

int run_conformance_command(ConformanceArgs& args) {
  ConformanceOptions& o = args.conformance;
  o.profile = args.options.profile == "spec" ? CompareProfile::Spec : CompareProfile::Lavapipe;
  make_cpu_options(args.options);  // a bad --method is a usage error before any work
  const RenderOptions render_options = args.options;
  o.cpu_options = [render_options](const Scene& scene) { return make_cpu_options(render_options, &scene); };
  o.vk = make_vk_options(args.options);
  if (!o.captures_root.empty() && !args.options.device.empty())
    throw UsageError("--captures: the device is the captures', not --device");
  if (!args.shard.empty()) o.shard = parse_shard(args.shard);

  const ConformancePlan plan = plan_conformance(o);
  fmt::print("conformance: {} case(s) of {} in the suite (shard {}/{}) → {}\n", plan.cases.size(), plan.suite_size,
             plan.shard.index, plan.shard.count, o.out_dir);
  std::fflush(stdout);
  StopOnSigint stop_on_sigint;
  const ConformanceResult result = run_conformance(o, plan, g_stop_requested, [](const std::string& line) {
    std::fputs(line.c_str(), stdout);
    std::fflush(stdout);
  });
  print_conformance_summary(stdout, result, o.out_dir);
  return result.exit_code;
}

}  // namespace

void add_conformance_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ConformanceArgs>();
  args->conformance.out_dir = "rastercmp-conformance";
  CLI::App* cmd = app.add_subcommand("conformance", "run a suite of scenes through compare, CTS/deqp-runner style");
  ConformanceOptions& o = args->conformance;
  cmd->add_option("--suite", o.suite_dir, "suite folder (every *.json below it); default: the built-in scenes/");
  cmd->add_option("--caselist", o.caselist_file, "run only the cases named in this file (one per line)");
  cmd->add_option("--case", o.case_globs, "run only cases whose name matches this glob (repeatable)");
  cmd->add_option("--baseline", o.baseline_file, "expected results, `name,Status` lines (Mesa *-fails.txt)");
  cmd->add_option("--flakes", o.flakes_file, "known flaky cases, one regex per line");
  cmd->add_option("--skips", o.skips_file, "cases not to run, one regex per line");
  cmd->add_option("--shard", args->shard,
                  "run shard I of N (0-based, interleaved); default from GTEST_SHARD_INDEX/GTEST_TOTAL_SHARDS");
  cmd->add_option("--out", o.out_dir, "output folder (results.csv, failures.csv, junit.xml, summary.json, report/)")
      ->capture_default_str();
  cmd->add_option("--captures", o.captures_root,
                  "judge the renders recorded below this folder (rastercmp capture --out) instead of rendering");
  add_render_options(*cmd, args->options);
  cmd->callback([args, &exit_code] { exit_code = run_conformance_command(*args); });
}

}  // namespace rastercmp::app
