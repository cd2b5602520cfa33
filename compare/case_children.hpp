// The parent side of a conformance run: cases run in child processes (`rastercmp
// conformance-worker`, compare/case_worker.hpp), a few per child, at most `jobs` children at a
// time, so that a driver that crashes or hangs costs one case, not the run:
//   a child that dies during a case (a signal, or an exit without its record) → Crash for that
//     case, with the signal or exit status and the child's last output lines; the cases it had
//     not begun go to a new child;
//   a case that runs past `timeout_s` (or a child that begins none within it) → the child is
//     killed (SIGKILL) and the case is Timeout, with the time and the last output lines;
//   a child that ends before beginning any case → its cases are Missing, with its output.
// A child that exits 2 (a report file could not be written) or 3 (no Vulkan) ends the run with
// the same error. Once `stop` is set no child is started, each running child is told to stop
// after its current case (SIGTERM), and the cases never begun are returned as not run.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "compare/case_record.hpp"

namespace rastercmp {

struct ChildCase {
  size_t id = 0;  // the caller's
  std::string scene_file;
};

enum class ChildEnd { Record, Crash, Timeout, Missing };

struct ChildOutcome {
  size_t id = 0;
  ChildEnd end = ChildEnd::Record;
  CaseRecord record;    // ChildEnd::Record: as the child wrote it (not judged)
  std::string message;  // otherwise: what happened, with the child's last output lines
  double duration_s = 0;
};

struct ChildRunOptions {
  std::vector<std::string> command;  // the worker command: executable, "conformance-worker", render options
  std::string report_dir;
  unsigned jobs = 1;
  double timeout_s = 60;
  size_t batch_size = 8;  // cases per child at most
};

// Runs every case; `done` is called in this thread as each ends (in completion order). Returns
// the ids not run because `stop` became non-zero, in the given order.
std::vector<size_t> run_in_children(const ChildRunOptions& options, const std::vector<ChildCase>& cases,
                                    const std::atomic<int>& stop, const std::function<void(ChildOutcome&&)>& done);

// The last `max_lines` lines of `text`, each prefixed with "  | ".
std::string last_lines(const std::string& text, size_t max_lines);

}  // namespace rastercmp
