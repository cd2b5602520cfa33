// Expected results in the Mesa CI style (deqp-runner): a baseline of `name,Status` lines,
// flakes and skips as one regular expression per line; `#` starts a comment line, blank lines
// are ignored. A case not in the baseline is expected to pass. The `#` lines directly above a
// baseline entry (no blank line between) are its reason, which the report shows beside it.
//
// Outcome of a case (its runner status):
//   result == expectation             → the result's name ("Pass", ...), or "ExpectedFail" for a failure
//   result differs, name matches a flake pattern → "KnownFlake"  (never fails the run)
//   failure expected, result is not a failure → "UnexpectedImprovement(<result>)" (fails the run)
//   result is a failure                → the result's name (fails the run)
//   otherwise (e.g. expected QualityWarning, got Pass) → the result's name
// QualityWarning and NotSupported are not failures (CTS / deqp-runner: Warn and Skip succeed).
#pragma once

#include <map>
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

struct Expectations {
  std::map<std::string, Verdict> baseline;
  std::map<std::string, std::string> reasons;  // baseline entry → its comment, "" when none
  std::vector<Pattern> flakes;
  std::vector<Pattern> skips;

  Verdict expected(const std::string& name) const;
  std::string reason(const std::string& name) const;
};

// Throws InputError(file, "line N", expected) on a malformed line, an unknown status or a
// duplicate name.
std::map<std::string, Verdict> parse_baseline(std::string_view text, const std::string& file);
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

Outcome judge_outcome(const std::string& name, Verdict result, const Expectations& expectations);

// Reads a whole text file. Throws InputError(path, "", ...) when it cannot.
std::string read_text_file(const std::string& path);

}  // namespace rastercmp
