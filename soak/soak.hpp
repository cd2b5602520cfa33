// The random differential soak (docs/soak.md): generate scenes family by family until a budget of
// primitives is spent, compare each against the Vulkan device, reduce each failure and write both
// the original and the reduced scene to the output folder.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "compare/case_run.hpp"
#include "soak/scene_gen.hpp"

namespace rastercmp::soak {

struct SoakOptions {
  uint64_t seed = 1;
  uint64_t primitives = 0;            // budget: scenes are generated until this many primitives ran
  std::vector<std::string> families;  // empty: all, in family_names() order
  std::string out_dir;                // empty: failures are counted, not written
  bool reduce = true;
  size_t max_reduce_runs = 1500;  // per failing scene
};

struct FamilyTally {
  std::string family;
  uint64_t scenes = 0, primitives = 0, passed = 0, not_supported = 0;
  std::map<std::string, uint64_t> failures;  // failure kind → scenes
  uint64_t failed() const;
};

struct SoakFailure {
  std::string family, name, kind;
  uint64_t primitives = 0, reduced_primitives = 0;
  size_t reduce_runs = 0;
  std::string original_path, reduced_path;  // empty when not written
};

struct SoakSummary {
  std::vector<FamilyTally> families;
  std::vector<SoakFailure> failures;
  uint64_t scenes = 0, primitives = 0;
  double compare_seconds = 0;  // generating and comparing
  double reduce_seconds = 0;   // reducing and writing failures
};

// Throws UsageError for an unknown family or a zero budget, InputError for an unwritable folder.
SoakSummary run_soak(CaseRunner& runner, const SoakOptions& options,
                     const std::function<void(const SoakFailure&)>& on_failure = {});

// The counts per family as a fixed-width table, and the totals with primitives per second.
std::string format_summary(const SoakSummary& summary);

}  // namespace rastercmp::soak
