// What a conformance run records about itself: the profile, the device judged, whether it was
// cut short and what it left unrun. Read by the machine-readable outputs and the report alike.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "compare/case_record.hpp"

namespace rastercmp {

struct RunInfo {
  std::string profile;               // "spec" or the lavapipe release reproduced: "lavapipe-25.0"
  std::string device;                // Vulkan device name
  std::string driver;                // driver info, e.g. "Mesa 22.3.6 (LLVM 15.0.6)"
  bool fma = false;                  // whether the CPU model fused (lavapipe on this host)
  bool complete = false;             // set only by the last write of a run that finished
  bool interrupted = false;          // stopped by a signal (SIGINT, SIGTERM, SIGHUP)
  std::vector<std::string> not_run;  // cases without a result yet (or ever), in run order
  std::string profile_warning;       // why the driver is judged by another release than its own
  // Which part of the selection this run is (--shard I/N), and how many cases the selection
  // (suite, --caselist, --case) held before sharding: merge checks that its shards are all there.
  uint32_t shard_index = 0, shard_count = 1;
  size_t selected_cases = 0;
  // Cases of shards that were never merged (merge --allow-missing): Missing, unnamed.
  size_t missing_unnamed = 0;
  bool operator==(const RunInfo&) const = default;
};

// Counts of the records per runner status, in name order.
std::map<std::string, size_t> count_statuses(const std::vector<CaseRecord>& records);
// Whether the run passes: complete, every case as expected and nothing left unrun.
bool run_passed(const RunInfo& info, const std::vector<CaseRecord>& records);

}  // namespace rastercmp
