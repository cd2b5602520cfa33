// The child side of a conformance run (compare/case_children.hpp): `rastercmp conformance-worker`
// renders, diffs and reports the scenes it is given, one after another in one process, and
// tells its parent about each on a pipe, one line per event:
//   begin<TAB>I                 case I (its position on the command line) has started
//   record<TAB>I<TAB>JSON       case I is done: case_to_json(record, true) on one line
// The parent judges the records against the expectations; a child only renders. SIGINT, SIGTERM
// and SIGHUP make it stop after the current case.
//
// TEST-ONLY faults: when the environment variable RASTERCMP_TEST_CASE_FAULT holds
// `KIND:CASE[;KIND:CASE...]`, the child, on starting case CASE, crashes (`crash`: raises SIGSEGV,
// as a faulting driver would), hangs (`hang`: sleeps for ever), exits with status 2 (`exit2`, as a
// driver that calls exit(2)), writes a line of its own into the result pipe (`stray_line`), forks a
// helper that holds the pipes and sleeps for ever (`helper`, its pid written to
// RASTERCMP_TEST_FAULT_DIR/CASE.helper), closes every descriptor and hangs (`close_fds_hang`) or,
// the first time only, reports a Fail (`fail_once`) or crashes and then reports a Fail every time
// after (`crash_then_fail`), remembered by creating the file RASTERCMP_TEST_FAULT_DIR/CASE. It
// exists so that tests/test_cli_children.cpp can check that a run survives these and tells a flake
// from a failure; any other value is an error (exit 4).
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "compare/case_run.hpp"

namespace rastercmp {

struct WorkerOptions {
  CompareProfile profile = CompareProfile::Lavapipe;
  CpuOptionsForScene cpu_options;
  VkOptions vk;
  std::string report_dir;  // where the case folders go (compare/report.hpp)
  int result_fd = -1;      // the pipe to the parent
  std::vector<std::string> scene_files;
  // Not empty: judge the captures below this folder (capture_dir_for with suite_dir) instead of
  // rendering on the device.
  std::string captures_root, suite_dir;
};

// Runs the scenes until done or `stop` is non-zero; returns 0. Throws InputError when a report file or the
// pipe cannot be written, EnvironmentError without a Vulkan device.
int run_case_worker(const WorkerOptions& options, const std::atomic<int>& stop);

}  // namespace rastercmp
