// `rastercmp conformance`: runs a suite of scenes through compare, judges each result against
// the expectations (baseline, flakes, skips) and keeps every output readable at every moment:
// results.csv is appended and flushed per case, the other files are rewritten atomically after
// each case. A stop request (SIGINT) finishes the current case, writes everything, lists what
// is left in not_run.txt and ends with exit 130.
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

inline constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as a shell reports it

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
};

struct ConformancePlan {
  std::vector<SuiteCase> cases;  // in run order (case name order, then the shard's stride)
  Expectations expectations;
  Shard shard;
  size_t suite_size = 0;  // cases in the suite before any filter
  std::string suite_dir;  // the suite folder read
};

// Checks the output folder (writable, or InputError before any work), reads the expectation
// files and the suite and selects the cases. Throws InputError / UsageError.
ConformancePlan plan_conformance(const ConformanceOptions& options);

struct ConformanceResult {
  RunInfo info;
  std::vector<CaseRecord> records;
  int exit_code = 0;  // 0 all as expected, 1 not, 130 interrupted
};

// Receives one progress line (with its newline) after each case: case n of N, its status, the
// counts so far, the time spent and an estimate of the time left.
using ProgressFn = std::function<void(const std::string& line)>;

// Runs the plan. `stop` is polled between cases. Throws EnvironmentError when no Vulkan device
// can be created, InputError when judging captures of which none has a readable render.json.
ConformanceResult run_conformance(const ConformanceOptions& options, const ConformancePlan& plan,
                                  const std::atomic<bool>& stop, const ProgressFn& progress);

// The closing summary: counts per status, the slowest cases, the report's path, and how to
// resume when interrupted.
void print_conformance_summary(std::FILE* out, const ConformanceResult& result, const std::string& out_dir);

// The run's description: profile, device, driver and whether the CPU model fuses.
RunInfo run_info_for(const CaseRunner& runner);

}  // namespace rastercmp
