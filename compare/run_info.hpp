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
  bool operator==(const RunInfo&) const = default;
};

// Counts of the records per runner status, in name order.
std::map<std::string, size_t> count_statuses(const std::vector<CaseRecord>& records);
// Whether the run passes: complete, every case as expected and nothing left unrun.
bool run_passed(const RunInfo& info, const std::vector<CaseRecord>& records);

}  // namespace rastercmp
