// `rastercmp conformance`: runs a suite of scenes through compare, each case in a child process
// with a timeout (compare/case_children.hpp), judges each result against the expectations
// (baseline, flakes, skips; compare/expectations.hpp), re-runs the cases that fail the run to
// tell a Flake from a failure, and keeps every output whole and honest at every moment: they are
// rewritten atomically after each case, in case order, with "complete": false and the cases
// without a result listed as Missing until the very end. --out is locked for the run. A stop
// request (SIGINT, SIGTERM, SIGHUP) finishes the running cases, writes everything, lists what is
// left in not_run.txt and ends with 128 + the signal's number.
#pragma once

#include <atomic>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "compare/case_record.hpp"
#include "compare/case_run.hpp"
#include "compare/case_select.hpp"
#include "compare/expectations.hpp"
#include "compare/run_outputs.hpp"

namespace rastercmp {

inline constexpr int kExitInterrupted = 130;        // 128 + SIGINT, as a shell reports it
inline constexpr double kDefaultCaseTimeoutS = 60;  // the slowest built-in case takes about 2 s

// The most child processes `conformance --jobs` runs at once (each holds a Vulkan device).
inline constexpr unsigned kMaxConformanceJobs = 256;

struct ConformanceOptions {
  std::string suite_dir;  // empty: default_suite_dir()
  std::string caselist_file;
  std::vector<std::string> case_globs;
  std::string baseline_file, flakes_file, skips_file;
  std::optional<Shard> shard;  // empty: GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS, else the whole suite
  std::string out_dir;
  CompareProfile profile = CompareProfile::Lavapipe;
  CpuOptionsForScene cpu_options;
  VkOptions vk;
  // Not empty: judge the renders recorded below this folder (rastercmp capture --out) instead of
  // rendering on a device; case PATH's capture is capture_dir_for(captures_root, suite, PATH).
  std::string captures_root;
  // The child command: the executable, "conformance-worker" and the render options (the same
  // profile and CPU options as above: the children render, this process only names the device).
  std::vector<std::string> worker_command;
  unsigned jobs = 1;                        // children at a time, 1 to kMaxConformanceJobs
  double timeout_s = kDefaultCaseTimeoutS;  // per case
  unsigned flake_retries = 1;               // re-runs of a case that fails the run
};

struct ConformancePlan {
  std::vector<SuiteCase> cases;         // in run order (case name order, then the shard's stride)
  std::vector<std::string> skipped_by;  // per case: the --skips pattern it matches, "" to run it
  Expectations expectations;
  Shard shard;
  size_t suite_size = 0;      // cases in the suite before any filter
  size_t selected_cases = 0;  // after --caselist and --case, before the shard
  std::string suite_dir;      // the suite folder read
};

// Checks the output folder (writable, or InputError before any work), reads the expectation
// files and the suite and selects the cases: case list, globs, shard, then the skips (a skipped
// case gets a Skip row, as in deqp-runner). Throws InputError / UsageError.
ConformancePlan plan_conformance(const ConformanceOptions& options);

struct ConformanceResult {
  RunInfo info;
  std::vector<CaseRecord> records;
  int exit_code = 0;  // 0 all as expected, 1 not, 128 + signal when stopped
};

// Holds --out for one run: an exclusive flock on OUT/.rastercmp.lock, which names the holder's
// pid while held and is emptied on release. Throws UsageError naming that pid when another run
// holds it.
class OutputLock {
 public:
  explicit OutputLock(const std::string& out_dir);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  int fd_ = -1;
};

// Removes the verdict files an earlier run left in --out (summary.json, results.csv, failures.csv,
// junit.xml, not_run.txt), so that a run killed before its first write never reads as that earlier
// run's pass. Called under the lock, before the suite is read. Returns how many it removed.
size_t remove_previous_verdict(const std::string& out_dir);

// Whether the process that named a temporary by its pid is gone (no such process; a pid out of
// range is no process either).
bool writer_gone(long long pid);

// Removes what an earlier run killed mid-write left in --out: temporary files (".NAME.tmpPID.EXT")
// and the re-run folder. Returns how many it removed.
size_t remove_stale_temporaries(const std::string& out_dir);

// Receives one progress line (with its newline) after each case: case n of N, its status, the
// counts so far, the time spent and an estimate of the time left.
using ProgressFn = std::function<void(const std::string& line)>;

// Runs the plan. `stop_signal` is polled between cases: non-zero, the number of the signal that
// asks to stop. Throws EnvironmentError when no Vulkan device can be created, InputError when
// judging captures of which none has a readable render.json.
ConformanceResult run_conformance(const ConformanceOptions& options, const ConformancePlan& plan,
                                  const std::atomic<int>& stop_signal, const ProgressFn& progress);

// The closing summary: counts per status, the slowest cases, the report's path, and, when
// interrupted, `resume_hint` (the commands to paste).
void print_conformance_summary(std::FILE* out, const ConformanceResult& result, const std::string& out_dir,
                               const std::string& resume_hint);

// The run's description: profile, device, driver and whether the CPU model fuses.
RunInfo run_info_for(const CaseRunner& runner);

}  // namespace rastercmp
