#include "compare/case_select.hpp"

#include <fmt/core.h>
#include <fnmatch.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "model/errors.hpp"
#include "model/mesh_import.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

std::optional<uint32_t> parse_uint(std::string_view text) {
  uint32_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

Shard checked_shard(std::optional<uint32_t> index, std::optional<uint32_t> count, const std::string& what) {
  if (!index || !count || *count == 0 || *index >= *count)
    throw UsageError(what + ": expected I/N with 0 <= I < N (0-based shard index I of N shards)");
  return Shard{*index, *count};
}

}  // namespace

std::vector<std::string> suite_dir_candidates(const std::string& executable) {
  const fs::path bin = fs::path(executable).parent_path();
  return {(bin / "scenes").string(), (bin / ".." / "share" / "rastercmp" / "scenes").lexically_normal().string()};
}

std::string default_suite_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const std::vector<std::string> candidates = suite_dir_candidates(ec ? std::string() : exe.string());
  for (const std::string& dir : candidates)
    if (fs::is_directory(dir, ec)) return dir;
  throw InputError(candidates.front(), "",
                   "expected the built-in suite next to the executable (" + candidates.front() + " or " +
                       candidates.back() + "); pass --suite DIR");
}

std::vector<std::string> find_scene_files(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir, "", "expected a suite folder with scene files (*.json)");
  std::vector<std::string> files;
  // Links to folders are followed (a suite made of other suites: the build's suite/ links the
  // built-in scenes beside the imported models), each real folder once, so a link cycle ends.
  std::set<fs::path> visited = {fs::canonical(dir, ec)};
  const auto options = fs::directory_options::follow_directory_symlink;
  for (auto it = fs::recursive_directory_iterator(dir, options, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_directory()) {
      std::error_code canonical_error;
      const bool first_visit = visited.insert(fs::canonical(it->path(), canonical_error)).second;
      // A folder that holds the lock file of a run's output (conformance --out, merge, capture) is
      // that output, never part of the suite: its summary.json and render.json files are no
      // scenes, even when --out lies inside --suite.
      if (!first_visit || canonical_error || fs::exists(it->path() / kOutputLockFile)) it.disable_recursion_pending();
      continue;
    }
    // Scene files, and model files (model/mesh_import.hpp), imported with the defaults.
    if (it->is_regular_file() && (it->path().extension() == ".json" || is_suite_model_file(it->path().string())))
      files.push_back(it->path().string());
  }
  if (ec) throw InputError(dir, "", "expected a readable folder: " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<SuiteCase> load_suite(const std::string& dir) {
  std::vector<SuiteCase> suite;
  for (const std::string& path : find_scene_files(dir)) {
    Scene scene = load_scene_or_model(path);
    std::string name = scene.name;
    suite.push_back({std::move(name), path, std::move(scene)});
  }
  if (suite.empty()) throw InputError(dir, "", "expected at least one scene file (*.json) in the suite");
  std::sort(suite.begin(), suite.end(), [](const SuiteCase& a, const SuiteCase& b) { return a.name < b.name; });
  for (size_t i = 1; i < suite.size(); ++i)
    if (suite[i].name == suite[i - 1].name)
      throw InputError(suite[i].path, "$.name",
                       "expected a case name of its own; " + suite[i - 1].path + " has the same: " + suite[i].name);
  return suite;
}

std::vector<std::string> parse_caselist(std::string_view text) {
  std::vector<std::string> names;
  while (!text.empty()) {
    const auto end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || line[first] == '#') continue;
    line = line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
    names.emplace_back(line);
  }
  return names;
}

bool glob_match(const std::string& pattern, const std::string& name) {
  return fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  if (slash == std::string::npos) return checked_shard(std::nullopt, std::nullopt, "--shard " + text);
  const std::string_view view(text);
  return checked_shard(parse_uint(view.substr(0, slash)), parse_uint(view.substr(slash + 1)), "--shard " + text);
}

std::optional<Shard> shard_from_environment() {
  const char* index = std::getenv("GTEST_SHARD_INDEX");
  const char* total = std::getenv("GTEST_TOTAL_SHARDS");
  if (index == nullptr || total == nullptr) return std::nullopt;
  return checked_shard(parse_uint(index), parse_uint(total),
                       fmt::format("GTEST_SHARD_INDEX={} GTEST_TOTAL_SHARDS={}", index, total));
}

std::vector<size_t> shard_positions(size_t n, Shard shard) {
  std::vector<size_t> positions;
  for (size_t i = shard.index; i < n; i += shard.count) positions.push_back(i);
  return positions;
}

std::vector<SuiteCase> select_cases(std::vector<SuiteCase> suite, const CaseFilter& filter,
                                    const std::string& caselist_file) {
  if (!filter.caselist.empty()) {
    const std::set<std::string> wanted(filter.caselist.begin(), filter.caselist.end());
    for (const std::string& name : wanted)
      if (std::none_of(suite.begin(), suite.end(), [&](const SuiteCase& c) { return c.name == name; }))
        throw InputError(caselist_file, "", "expected case names of the suite; it has no case " + name);
    std::erase_if(suite, [&](const SuiteCase& c) { return !wanted.count(c.name); });
  }
  if (!filter.globs.empty())
    std::erase_if(suite, [&](const SuiteCase& c) {
      return std::none_of(filter.globs.begin(), filter.globs.end(),
                          [&](const std::string& g) { return glob_match(g, c.name); });
    });
  std::erase_if(suite, [&](const SuiteCase& c) { return matches_any(filter.skips, c.name); });
  return suite;
}

std::vector<SuiteCase> take_shard(std::vector<SuiteCase> cases, Shard shard) {
  std::vector<SuiteCase> selected;
  for (size_t position : shard_positions(cases.size(), shard)) selected.push_back(std::move(cases[position]));
  return selected;
}

}  // namespace rastercmp
