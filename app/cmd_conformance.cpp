// rastercmp conformance [--suite DIR] [--caselist FILE] [--case GLOB] [--baseline FILE]
//   [--flakes FILE] [--skips FILE] [--shard I/N] [--out DIR] [--jobs N] [--timeout S]
//   [--flake-retries N] [--profile ...] [--device ...] [--validate] [--threads N] [--captures ROOT]
// Runs a suite through compare (compare/conformance.hpp), each case in a child process: the
// hidden `rastercmp conformance-worker` (compare/case_worker.hpp). SIGINT, SIGTERM and SIGHUP
// finish the running cases, write every output and exit 128 + the signal with the commands to
// resume.
#include <fmt/core.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "compare/case_worker.hpp"
#include "compare/conformance.hpp"
#include "model/errors.hpp"

namespace rastercmp::app {
namespace {

// Set by the handler to the signal's number, polled between cases (a lock-free atomic is
// signal-safe).
std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void request_stop(int signal) {
  int none = 0;
  g_stop_signal.compare_exchange_strong(none, signal);
}

// Installs the handler for SIGINT, SIGTERM and SIGHUP for the lifetime of the run. A SIGHUP the
// caller set to be ignored stays ignored: `nohup rastercmp conformance` survives the hang-up, as
// nohup promises. (SIGINT is taken whatever it was: a shell's background job starts with it
// ignored, and a run must still stop on it when sent.)
class StopOnSignals {
 public:
  StopOnSignals() {
    g_stop_signal.store(0);
    struct sigaction action {};
    action.sa_handler = request_stop;
    action.sa_flags = SA_RESTART;  // a wait inside the driver goes on; the flag is read between cases
    sigemptyset(&action.sa_mask);
    for (size_t i = 0; i < kSignals.size(); ++i) {
      sigaction(kSignals[i], nullptr, &previous_[i]);
      if (kSignals[i] != SIGHUP || previous_[i].sa_handler != SIG_IGN) sigaction(kSignals[i], &action, nullptr);
    }
  }
  ~StopOnSignals() {
    for (size_t i = 0; i < kSignals.size(); ++i) sigaction(kSignals[i], &previous_[i], nullptr);
  }
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  static constexpr std::array<int, 3> kSignals = {SIGINT, SIGTERM, SIGHUP};
  std::array<struct sigaction, 3> previous_{};
};

struct ConformanceArgs {
  ConformanceOptions conformance;
  std::string shard;
  RenderOptions options;
};

// The render options as command-line arguments (for the children and the resume command).
std::vector<std::string> render_arguments(const RenderOptions& o) {
  std::vector<std::string> args = {"--profile", o.profile, "--fma", o.fma, "--threads", std::to_string(o.threads)};
  for (const std::string& m : o.methods) args.insert(args.end(), {"--method", m});
  if (!o.device.empty()) args.insert(args.end(), {"--device", o.device});
  if (o.validate) args.push_back("--validate");
  return args;
}

std::string executable_path() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the running executable (/proc/self/exe): " + ec.message());
  return self.string();
}

// Single-quoted for a POSIX shell when it holds anything but [A-Za-z0-9_./=:,+-].
std::string shell_quote(const std::string& word) {
  if (!word.empty() &&
      word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./=:,+-@%") ==
          std::string::npos)
    return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string command_line(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& w : words) line += (line.empty() ? "" : " ") + shell_quote(w);
  return line;
}

// The two commands that finish an interrupted run: the same run over not_run.txt into a new
// folder (one shard: the list is already this shard's), then a merge of both folders.
std::string resume_hint(const ConformanceArgs& args, const std::string& exe) {
  const ConformanceOptions& o = args.conformance;
  const std::string out = std::filesystem::path(o.out_dir).lexically_normal().string();
  const std::string out_base = out.size() > 1 && out.back() == '/' ? out.substr(0, out.size() - 1) : out;
  const std::string resumed = out_base + "-resumed", merged = out_base + "-merged";
  std::vector<std::string> run = {exe, "conformance"};
  if (!o.suite_dir.empty()) run.insert(run.end(), {"--suite", o.suite_dir});
  run.insert(run.end(), {"--caselist", (std::filesystem::path(o.out_dir) / "not_run.txt").string()});
  if (!o.baseline_file.empty()) run.insert(run.end(), {"--baseline", o.baseline_file});
  if (!o.flakes_file.empty()) run.insert(run.end(), {"--flakes", o.flakes_file});
  if (!o.skips_file.empty()) run.insert(run.end(), {"--skips", o.skips_file});
  if (!o.captures_root.empty()) run.insert(run.end(), {"--captures", o.captures_root});
  run.insert(run.end(), {"--shard", "0/1", "--jobs", std::to_string(o.jobs), "--timeout",
                         fmt::format("{:g}", o.timeout_s), "--flake-retries", std::to_string(o.flake_retries)});
  const std::vector<std::string> render = render_arguments(args.options);
  run.insert(run.end(), render.begin(), render.end());
  run.insert(run.end(), {"--out", resumed});
  const std::vector<std::string> merge = {exe, "merge", merged, o.out_dir, resumed};
  return fmt::format("resume with:\n  {}\nthen merge:\n  {}\n", command_line(run), command_line(merge));
}

int run_conformance_command(ConformanceArgs& args) {
  // Signals first: a stop at any moment from here on is recorded as an interrupted run.
  StopOnSignals stop_on_signals;
  ConformanceOptions& o = args.conformance;
  // An earlier run's verdict goes before anything else is read, under the lock, so that this run,
  // killed at any moment (kill -9 during the suite's load or the device probe), never reads as
  // that run's pass. A fresh folder is left alone until the input has been checked.
  std::optional<OutputLock> lock;
  if (std::filesystem::exists(std::filesystem::path(o.out_dir) / "summary.json")) {
    lock.emplace(o.out_dir);
    remove_previous_verdict(o.out_dir);
  }
  o.profile = args.options.profile == "spec" ? CompareProfile::Spec : CompareProfile::Lavapipe;
  make_cpu_options(args.options);  // a bad --method is a usage error before any work
  const RenderOptions render_options = args.options;
  o.cpu_options = [render_options](const Scene& scene) { return make_cpu_options(render_options, &scene); };
  o.vk = make_vk_options(args.options);
  if (!o.captures_root.empty() && !args.options.device.empty())
    throw UsageError("--captures: the device is the captures', not --device");
  if (!args.shard.empty()) o.shard = parse_shard(args.shard);
  if (!(o.timeout_s > 0)) throw UsageError("--timeout: expected a number of seconds above 0");
  if (o.jobs == 0) throw UsageError("--jobs: expected 1 or more");
  const std::string exe = executable_path();
  o.worker_command = {exe, "conformance-worker"};
  const std::vector<std::string> render = render_arguments(args.options);
  o.worker_command.insert(o.worker_command.end(), render.begin(), render.end());

  const ConformancePlan plan = plan_conformance(o);  // bad input: exit 2 before any file is written
  for (const SuiteCase& c : plan.cases) check_scene_methods(c.scene, c.path);  // a bad "methods" is exit 2
  if (!o.captures_root.empty())  // the children judge the captures: where each case's lies
    o.worker_command.insert(o.worker_command.end(), {"--captures", o.captures_root, "--suite-dir", plan.suite_dir});
  if (!lock) lock.emplace(o.out_dir);  // a second run into the same folder: exit 2 naming this one
  if (const size_t stale = remove_stale_temporaries(o.out_dir); stale != 0)
    fmt::print(stderr, "note: removed {} temporary file(s) an earlier run left in {}\n", stale, o.out_dir);
  fmt::print("conformance: {} case(s) of {} in the suite (shard {}/{}) → {}\n", plan.cases.size(), plan.suite_size,
             plan.shard.index, plan.shard.count, o.out_dir);
  std::fflush(stdout);
  // A child killed before its case ended (the run stopped by a failed write or a signal, or the
  // case past its timeout) leaves the temporary image it was writing: once run_conformance has
  // reaped every child, whether it returns or throws, their temporaries go too.
  struct SweepTemporaries {
    const std::string& out_dir;
    ~SweepTemporaries() {
      try {
        remove_stale_temporaries(out_dir);
      } catch (const std::exception&) {  // nothing more to do on the way out
      }
    }
  } sweep{o.out_dir};
  const ConformanceResult result = run_conformance(o, plan, g_stop_signal, [](const std::string& line) {
    std::fputs(line.c_str(), stdout);
    std::fflush(stdout);
  });
  print_conformance_summary(stdout, result, o.out_dir, resume_hint(args, exe));
  return result.exit_code;
}

struct WorkerArgs {
  RenderOptions options;
  std::string report_dir;
  int result_fd = -1;
  std::vector<std::string> scene_files;
  std::string captures_root, suite_dir;
};

int run_worker_command(const WorkerArgs& args) {
  WorkerOptions w;
  w.profile = args.options.profile == "spec" ? CompareProfile::Spec : CompareProfile::Lavapipe;
  const RenderOptions render_options = args.options;
  w.cpu_options = [render_options](const Scene& scene) { return make_cpu_options(render_options, &scene); };
  w.vk = make_vk_options(args.options);
  w.report_dir = args.report_dir;
  w.result_fd = args.result_fd;
  w.scene_files = args.scene_files;
  w.captures_root = args.captures_root;
  w.suite_dir = args.suite_dir;
  StopOnSignals stop_on_signals;  // the parent's SIGTERM (or the terminal's SIGINT): stop after this case
  return run_case_worker(w, g_stop_signal);
}

}  // namespace

void add_conformance_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ConformanceArgs>();
  args->conformance.out_dir = "out/conformance";
  CLI::App* cmd = app.add_subcommand("conformance", "run a suite of scenes through compare, CTS/deqp-runner style");
  ConformanceOptions& o = args->conformance;
  cmd->add_option("--suite", o.suite_dir, "suite folder (every *.json below it); default: the built-in scenes/");
  cmd->add_option("--caselist", o.caselist_file, "run only the cases named in this file (one per line)");
  cmd->add_option("--case", o.case_globs, "run only cases whose name matches this glob (repeatable)");
  cmd->add_option("--baseline", o.baseline_file, "expected results, `name,Status` lines (Mesa *-fails.txt)");
  cmd->add_option("--flakes", o.flakes_file, "known flaky cases, one regex per line");
  cmd->add_option("--skips", o.skips_file, "cases not to run (a Skip row each), one regex per line");
  cmd->add_option("--shard", args->shard,
                  "run shard I of N (0-based, interleaved); default from GTEST_SHARD_INDEX/GTEST_TOTAL_SHARDS");
  cmd->add_option("--out", o.out_dir, "output folder (results.csv, failures.csv, junit.xml, summary.json, report/)")
      ->capture_default_str();
  cmd->add_option("--captures", o.captures_root,
                  "judge the renders recorded below this folder (rastercmp capture --out) instead of rendering");
  cmd->add_option("--jobs", o.jobs, "cases run at the same time, each in its own child process (at most 256)")
      ->check(CLI::Range(1u, kMaxConformanceJobs))
      ->capture_default_str();
  cmd->add_option("--timeout", o.timeout_s, "seconds a case may take before it is killed and recorded as Timeout")
      ->capture_default_str();
  cmd->add_option("--flake-retries", o.flake_retries,
                  "re-runs of a case that fails the run; another status on a re-run makes it a Flake")
      ->capture_default_str();
  add_render_options(*cmd, args->options);
  cmd->callback([args, &exit_code] { exit_code = run_conformance_command(*args); });

  // The child of a conformance run; hidden from --help (an empty group).
  auto worker = std::make_shared<WorkerArgs>();
  CLI::App* w = app.add_subcommand("conformance-worker", "internal: runs cases for rastercmp conformance");
  w->group("");
  w->add_option("--report", worker->report_dir)->required();
  w->add_option("--result-fd", worker->result_fd)->required();
  w->add_option("scenes", worker->scene_files)->required();
  w->add_option("--captures", worker->captures_root);
  w->add_option("--suite-dir", worker->suite_dir);
  add_render_options(*w, worker->options);
  w->callback([worker, &exit_code] { exit_code = run_worker_command(*worker); });
}

}  // namespace rastercmp::app
