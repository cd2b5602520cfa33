// Which cases a conformance run takes: the suite (every *.json below a folder, ordered by case
// name), narrowed by a case list, name globs and skip patterns, then split into interleaved
// shards (case i, i+N, i+2N, ... for shard i of N; deqp-runner --fraction, GTEST_SHARD_INDEX).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compare/expectations.hpp"
#include "model/scene.hpp"

namespace rastercmp {

struct SuiteCase {
  std::string name;  // Scene::name, the case id
  std::string path;  // the scene file
  Scene scene;
};

// Where the built-in suite may lie for an executable at `executable`, in the order searched:
// <executable's folder>/scenes (the build tree: a link to the source tree's scenes/, made by
// app/CMakeLists.txt), then <executable's folder>/../share/rastercmp/scenes (an installed copy).
std::vector<std::string> suite_dir_candidates(const std::string& executable);

// The first of suite_dir_candidates(the running executable) that is a folder. Found at run time,
// so a moved or installed binary finds its suite; throws InputError naming both places otherwise.
std::string default_suite_dir();

// The lock file a run's output folder holds (compare/conformance.hpp OutputLock).
inline constexpr const char* kOutputLockFile = ".rastercmp.lock";

// Every regular file named *.json below `dir`, recursively, in path order, except below a folder
// that holds kOutputLockFile (a run's output). Throws InputError when `dir` is not a folder.
std::vector<std::string> find_scene_files(const std::string& dir);

// Loads every scene of the suite, ordered by case name. Throws InputError for a bad scene file,
// an empty suite or two files with the same case name.
std::vector<SuiteCase> load_suite(const std::string& dir);

// A case list: one case name per line, `#` comments and blank lines ignored.
std::vector<std::string> parse_caselist(std::string_view text);

// Shell-style glob over a case name (`*`, `?`, `[...]`; fnmatch without flags).
bool glob_match(const std::string& pattern, const std::string& name);

struct Shard {
  uint32_t index = 0;  // 0-based
  uint32_t count = 1;
  bool operator==(const Shard&) const = default;
};

// "I/N" with 0 <= I < N. Throws UsageError.
Shard parse_shard(const std::string& text);
// GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS when both are set; throws UsageError when malformed.
std::optional<Shard> shard_from_environment();

// Positions 0..n-1 that belong to a shard: index, index + count, ...
std::vector<size_t> shard_positions(size_t n, Shard shard);

struct CaseFilter {
  std::vector<std::string> caselist;  // empty: every case
  std::vector<std::string> globs;     // empty: every case; else a name must match one
  std::vector<Pattern> skips;
};

// Applies the filter in that order (case list, globs, skips). Throws InputError when a case
// list names a case the suite does not have.
std::vector<SuiteCase> select_cases(std::vector<SuiteCase> suite, const CaseFilter& filter,
                                    const std::string& caselist_file);

// The cases of one shard, in order.
std::vector<SuiteCase> take_shard(std::vector<SuiteCase> cases, Shard shard);

}  // namespace rastercmp
