#include "compare/expectations.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include "model/errors.hpp"
#include "model/file_read.hpp"

namespace rastercmp {
namespace {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// Calls `line_fn(line_number, line)` for every line that is neither blank nor a comment.
template <typename Fn>
void for_each_content_line(std::string_view text, Fn line_fn) {
  size_t line_number = 0;
  while (!text.empty()) {
    const auto end = text.find('\n');
    const std::string_view line = trim(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++line_number;
    if (line.empty() || line.front() == '#') continue;
    line_fn(line_number, line);
  }
}

std::string line_path(size_t line_number) { return fmt::format("line {}", line_number); }

}  // namespace

std::string runner_status(Verdict verdict) {
  switch (verdict) {
    case Verdict::Pass: return "Pass";
    case Verdict::QualityWarning: return "Warn";
    case Verdict::NotSupported: return "Skip";
    case Verdict::Crash: return "Crash";
    case Verdict::Timeout: return "Timeout";
    case Verdict::Fail:
    case Verdict::ResourceError:
    case Verdict::InternalError: return "Fail";
  }
  return "Fail";
}

std::string Expectations::reason(const std::string& name) const {
  const auto it = reasons.find(name);
  return it == reasons.end() ? std::string() : it->second;
}

std::map<std::string, std::string> parse_baseline_reasons(std::string_view text) {
  std::map<std::string, std::string> reasons;
  std::string comment;  // the comment lines since the last blank line or entry
  while (!text.empty()) {
    const auto end = text.find('\n');
    const std::string_view line = trim(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    if (!line.empty() && line.front() == '#') {
      const std::string_view words = trim(line.substr(1));
      if (!words.empty() && !comment.empty()) comment += ' ';
      comment.append(words);
      continue;
    }
    const auto comma = line.rfind(',');
    if (!line.empty() && comma != std::string_view::npos && !comment.empty())
      reasons.emplace(std::string(trim(line.substr(0, comma))), comment);
    comment.clear();
  }
  return reasons;
}

bool is_success_status(std::string_view status) {
  return status == "Pass" || status == "Skip" || status == "Warn" || status == "Flake" || status == "KnownFlake" ||
         status == "ExpectedFail";
}

std::optional<std::string> parse_runner_status(std::string_view name) {
  static constexpr std::string_view kPlain[] = {"Pass",       "Fail", "Skip",    "Crash",        "Flake",
                                                "KnownFlake", "Warn", "Missing", "ExpectedFail", "Timeout"};
  static constexpr std::string_view kTestStatuses[] = {"Pass", "Fail", "Crash", "Skip", "Warn", "Timeout"};
  for (std::string_view s : kPlain)
    if (name == s) return std::string(s);
  constexpr std::string_view prefix = "UnexpectedImprovement(";
  if (name.size() > prefix.size() + 1 && name.substr(0, prefix.size()) == prefix && name.back() == ')') {
    const std::string_view inner = name.substr(prefix.size(), name.size() - prefix.size() - 1);
    for (std::string_view s : kTestStatuses)
      if (inner == s) return std::string(name);
  }
  if (const auto verdict = parse_verdict(name)) return runner_status(*verdict);
  return std::nullopt;
}

std::string Expectations::expected(const std::string& name) const {
  const auto it = baseline.find(name);
  return it == baseline.end() ? "Pass" : it->second;
}

std::map<std::string, std::string> parse_baseline(std::string_view text, const std::string& file) {
  std::map<std::string, std::string> baseline;
  for_each_content_line(text, [&](size_t n, std::string_view line) {
    const auto comma = line.rfind(',');  // the status never holds a comma; a name might
    if (comma == std::string_view::npos)
      throw InputError(file, line_path(n), "expected `name,Status`, found `" + std::string(line) + "`");
    const std::string name(trim(line.substr(0, comma)));
    const std::string status(trim(line.substr(comma + 1)));
    const auto parsed = parse_runner_status(status);
    if (name.empty() || !parsed)
      throw InputError(file, line_path(n),
                       "expected `name,Status` with Status a deqp-runner status (Pass, Fail, Skip, Crash, Timeout, "
                       "Warn, Flake, KnownFlake, Missing, ExpectedFail, UnexpectedImprovement(Pass)) or a CTS "
                       "result name; found `" +
                           std::string(line) + "`");
    if (!baseline.emplace(name, *parsed).second)
      throw InputError(file, line_path(n), "expected each case once; `" + name + "` is listed again");
  });
  return baseline;
}

namespace {

// std::regex compiles and matches by recursion, so a pattern long or deeply nested enough
// overflows the stack (a 100,000-character line, 30,000 nested parentheses). Case names are short:
// these bounds are far above any useful pattern.
constexpr size_t kMaxPatternLength = 1000;
constexpr size_t kMaxPatternNesting = 16;

// "" when the pattern is within the bounds, else what is wrong with it.
std::string pattern_bounds_problem(std::string_view line) {
  if (line.size() > kMaxPatternLength)
    return "expected a regular expression of at most " + std::to_string(kMaxPatternLength) + " characters, found " +
           std::to_string(line.size());
  size_t depth = 0, deepest = 0;
  bool in_class = false;
  for (size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (c == '\\') {
      ++k;  // an escaped character
    } else if (in_class) {
      in_class = c != ']';
    } else if (c == '[') {
      in_class = true;
    } else if (c == '(') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ')' && depth > 0) {
      --depth;
    }
  }
  if (deepest > kMaxPatternNesting)
    return "expected a regular expression nested at most " + std::to_string(kMaxPatternNesting) +
           " groups deep, found " + std::to_string(deepest);
  return "";
}

}  // namespace

std::vector<Pattern> parse_patterns(std::string_view text, const std::string& file) {
  std::vector<Pattern> patterns;
  for_each_content_line(text, [&](size_t n, std::string_view line) {
    if (const std::string problem = pattern_bounds_problem(line); !problem.empty())
      throw InputError(file, line_path(n), problem);
    try {
      patterns.push_back({std::string(line), std::regex(std::string(line), std::regex::ECMAScript)});
    } catch (const std::regex_error& e) {
      throw InputError(file, line_path(n),
                       "expected a regular expression, found `" + std::string(line) + "` (" + e.what() + ")");
    }
  });
  return patterns;
}

std::string read_text_file(const std::string& path) {
  return read_bounded_file(path, kMaxListFileBytes, "a list file (baseline, flakes, skips, caselist, results)");
}

Expectations load_expectations(const std::string& baseline_file, const std::string& flakes_file,
                               const std::string& skips_file) {
  Expectations e;
  if (!baseline_file.empty()) {
    const std::string text = read_text_file(baseline_file);
    e.baseline = parse_baseline(text, baseline_file);
    e.reasons = parse_baseline_reasons(text);
  }
  if (!flakes_file.empty()) e.flakes = parse_patterns(read_text_file(flakes_file), flakes_file);
  if (!skips_file.empty()) e.skips = parse_patterns(read_text_file(skips_file), skips_file);
  return e;
}

bool matches_any(const std::vector<Pattern>& patterns, const std::string& name) {
  for (const Pattern& p : patterns)
    if (std::regex_search(name, p.regex)) return true;
  return false;
}

std::string with_baseline(const std::string& status, const std::string& baseline) {
  const auto is = [&](std::initializer_list<std::string_view> names) {
    return std::find(names.begin(), names.end(), baseline) != names.end();
  };
  const auto improved = [&] { return "UnexpectedImprovement(" + status + ")"; };
  if (baseline.empty()) return status;
  if (status == "Fail")
    return is({"Fail", "ExpectedFail"}) ? "ExpectedFail" : is({"Crash", "Timeout"}) ? improved() : status;
  if (status == "Pass") return is({"Fail", "Crash", "Missing", "Timeout"}) ? improved() : status;
  if (status == "Crash") return is({"Crash", "ExpectedFail"}) ? "ExpectedFail" : status;
  if (status == "Warn") return is({"Fail", "Crash"}) ? improved() : is({"Warn"}) ? "ExpectedFail" : status;
  if (status == "Skip") return is({"Fail", "Crash", "Missing", "Timeout"}) ? improved() : status;
  if (status == "Timeout") return is({"Timeout"}) ? "ExpectedFail" : status;
  return status;
}

Outcome judge_outcome(const std::string& name, Verdict result, const Expectations& expectations) {
  const auto listed = expectations.baseline.find(name);
  std::string status =
      with_baseline(runner_status(result), listed == expectations.baseline.end() ? "" : listed->second);
  if (!is_success_status(status) && matches_any(expectations.flakes, name)) status = "KnownFlake";
  const bool fails = !is_success_status(status);
  return {std::move(status), fails};
}

}  // namespace rastercmp
