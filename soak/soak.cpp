#include "soak/soak.hpp"

#include <fmt/core.h>

#include <chrono>
#include <filesystem>

#include "model/errors.hpp"
#include "model/image_io.hpp"
#include "soak/judge.hpp"
#include "soak/primitives.hpp"
#include "soak/reduce.hpp"
#include "soak/scene_write.hpp"

namespace rastercmp::soak {

uint64_t FamilyTally::failed() const {
  uint64_t n = 0;
  for (const auto& [kind, count] : failures) n += count;
  return n;
}

SoakSummary run_soak(CaseRunner& runner, const SoakOptions& options,
                     const std::function<void(const SoakFailure&)>& on_failure) {
  const std::vector<std::string> families = options.families.empty() ? family_names() : options.families;
  for (const std::string& f : families)
    if (!is_family(f)) {
      std::string all;
      for (const std::string& n : family_names()) all += (all.empty() ? "" : ", ") + n;
      throw UsageError(fmt::format("--family {}: unknown family (families: {})", f, all));
    }
  if (options.primitives == 0) throw UsageError("--count: expected a number of primitives >= 1, found 0");
  if (!options.out_dir.empty()) ensure_output_dir(options.out_dir);
  break_model_enabled();  // a bad RASTERCMP_TEST_BREAK_MODEL fails before any work

  SoakSummary summary;
  for (const std::string& f : families) {
    FamilyTally tally;
    tally.family = f;
    summary.families.push_back(tally);
  }
  using Clock = std::chrono::steady_clock;
  for (uint64_t index = 0; summary.primitives < options.primitives; ++index) {
    const auto start = Clock::now();
    FamilyTally& tally = summary.families[index % families.size()];
    const Scene scene = generate_scene(tally.family, options.seed, index);
    const uint64_t prims = primitive_count(scene);
    const CaseResult result = judge(runner, scene);
    const std::string kind = failure_kind(result);
    ++summary.scenes;
    summary.primitives += prims;
    ++tally.scenes;
    tally.primitives += prims;
    if (!kind.empty()) {
      ++tally.failures[kind];
    } else if (result.verdict == Verdict::NotSupported) {
      ++tally.not_supported;
    } else {
      ++tally.passed;
    }
    const auto compared = Clock::now();
    summary.compare_seconds += std::chrono::duration<double>(compared - start).count();
    if (kind.empty()) continue;

    SoakFailure failure;
    failure.family = tally.family;
    failure.name = scene.name;
    failure.kind = kind;
    failure.primitives = failure.reduced_primitives = prims;
    Scene reduced = scene;
    if (options.reduce) {
      ReduceStats stats;
      reduced = reduce_scene(
          scene, [&](const Scene& s) { return failure_kind(judge(runner, s)) == kind; }, options.max_reduce_runs,
          &stats);
      reduced.description = fmt::format("{} (reduced from {} primitives, {} failure)", scene.description, prims, kind);
      failure.reduced_primitives = stats.primitives_after;
      failure.reduce_runs = stats.runs;
    }
    if (!options.out_dir.empty()) {
      const std::filesystem::path dir(options.out_dir);
      failure.original_path = (dir / (scene.name + ".original.json")).string();
      write_scene_file(failure.original_path, scene);
      if (options.reduce) {
        failure.reduced_path = (dir / (scene.name + ".json")).string();
        write_scene_file(failure.reduced_path, reduced);
      }
    }
    summary.reduce_seconds += std::chrono::duration<double>(Clock::now() - compared).count();
    if (on_failure) on_failure(failure);
    summary.failures.push_back(std::move(failure));
  }
  return summary;
}

std::string format_summary(const SoakSummary& summary) {
  std::string text = fmt::format("{:<12} {:>8} {:>10} {:>8} {:>8} {:>6}  failures by kind\n", "family", "scenes",
                                 "primitives", "passed", "failed", "n/s");
  uint64_t failed = 0;
  for (const FamilyTally& t : summary.families) {
    std::string kinds;
    for (const auto& [kind, count] : t.failures)
      kinds += fmt::format("{}{} {}", kinds.empty() ? "" : ", ", kind, count);
    text += fmt::format("{:<12} {:>8} {:>10} {:>8} {:>8} {:>6}  {}\n", t.family, t.scenes, t.primitives, t.passed,
                        t.failed(), t.not_supported, kinds);
    failed += t.failed();
  }
  const double rate = summary.compare_seconds > 0 ? double(summary.primitives) / summary.compare_seconds : 0;
  text += fmt::format(
      "total: {} scenes, {} primitives, {} failed; compare {:.1f} s ({:.0f} primitives/s), reduce {:.1f} s\n",
      summary.scenes, summary.primitives, failed, summary.compare_seconds, rate, summary.reduce_seconds);
  return text;
}

}  // namespace rastercmp::soak
