// Expected results in the Mesa CI style (deqp-runner): a baseline of `name,Status` lines,
// flakes and skips as one regular expression per line; `#` starts a comment line, blank lines
// are ignored. A case not in the baseline is expected to pass. The `#` lines directly above a
// baseline entry (no blank line between) are its reason, which the report shows beside it.
//
// Statuses are deqp-runner's RunnerStatus names (src/runner_results.rs): a case's verdict
// becomes Pass, Fail (Fail, ResourceError, InternalError), Warn (QualityWarning), Skip
// (NotSupported), Crash or Timeout, and is then judged against the baseline exactly as
// deqp-runner's with_baseline does:
//   Fail    with baseline Fail or ExpectedFail → ExpectedFail; Crash or Timeout → UnexpectedImprovement(Fail)
//   Pass    with baseline Fail, Crash, Missing or Timeout → UnexpectedImprovement(Pass)
//   Crash   with baseline Crash or ExpectedFail → ExpectedFail
//   Warn    with baseline Fail or Crash → UnexpectedImprovement(Warn); Warn → ExpectedFail
//   Skip    with baseline Fail, Crash, Missing or Timeout → UnexpectedImprovement(Skip)
//   Timeout with baseline Timeout → ExpectedFail
//   otherwise the status itself.
// A status that fails the run (Fail, Crash, Timeout, Missing, UnexpectedImprovement(...)) on a
// case whose name matches a flakes pattern becomes KnownFlake. Pass, Skip, Warn, Flake,
// KnownFlake and ExpectedFail do not fail the run. Flake (a case whose re-run gave another
// status) and Missing (a case that gave no result) are set by the runner (compare/conformance.hpp).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

#include "compare/verdict.hpp"

namespace rastercmp {

struct Pattern {
  std::string text;
  std::regex regex;
};

// deqp-runner's name for a verdict's result (RunnerStatus::from_deqp).
std::string runner_status(Verdict verdict);
// deqp-runner's RunnerStatus::is_success: false for Fail, Crash, Timeout, Missing and
// UnexpectedImprovement(...).
bool is_success_status(std::string_view status);
// A RunnerStatus name, or one of the CTS names a baseline of older rastercmp versions used
// (QualityWarning → Warn, NotSupported → Skip, ResourceError and InternalError → Fail).
std::optional<std::string> parse_runner_status(std::string_view name);

struct Expectations {
  std::map<std::string, std::string> baseline;  // name → runner status
  std::map<std::string, std::string> reasons;   // baseline entry → its comment, "" when none
  std::vector<Pattern> flakes;
  std::vector<Pattern> skips;

  // The baseline's status, "Pass" for a case it does not list.
  std::string expected(const std::string& name) const;
  std::string reason(const std::string& name) const;
};

// Throws InputError(file, "line N", expected) on a malformed line, an unknown status or a
// duplicate name.
std::map<std::string, std::string> parse_baseline(std::string_view text, const std::string& file);
// Entry name → the text of the `#` lines directly above it (without the `#`, joined by a space);
// entries without such lines are left out. Reads only what parse_baseline accepts.
std::map<std::string, std::string> parse_baseline_reasons(std::string_view text);
// Throws InputError on an invalid regular expression.
std::vector<Pattern> parse_patterns(std::string_view text, const std::string& file);

// Reads the files; an empty path means none. Throws InputError for an unreadable file.
Expectations load_expectations(const std::string& baseline_file, const std::string& flakes_file,
                               const std::string& skips_file);

// A pattern matches when it matches any part of the name (Rust regex is_match, as deqp-runner).
bool matches_any(const std::vector<Pattern>& patterns, const std::string& name);

struct Outcome {
  std::string status;
  bool fails_run = false;
};

// The status of a result against the baseline (with_baseline), then KnownFlake when it fails the
// run and the name matches a flakes pattern.
Outcome judge_outcome(const std::string& name, Verdict result, const Expectations& expectations);
// with_baseline alone: `status` from runner_status(), `baseline` a RunnerStatus name ("" = not listed).
std::string with_baseline(const std::string& status, const std::string& baseline);

// The most a list file (--baseline, --flakes, --skips, --caselist) or a run's results.csv and
// summary.json may hold: far above a suite of a million cases.
inline constexpr uint64_t kMaxListFileBytes = uint64_t(256) << 20;

// Reads a whole text file: a regular file of at most kMaxListFileBytes (model/file_read.hpp).
// Throws InputError(path, "", ...) when it cannot.
std::string read_text_file(const std::string& path);

}  // namespace rastercmp
