// `rastercmp merge OUT_DIR SHARD_DIR...`: joins the outputs of conformance runs over disjoint
// case sets (shards of one suite, or a run and its resumption) into one folder, as if one run
// had produced them: results.csv, failures.csv, junit.xml, summary.json and the report (the
// cases' image folders are copied). Cases are ordered by name, as a whole run orders them.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "compare/run_outputs.hpp"

namespace rastercmp {

struct MergeResult {
  RunInfo info;
  std::vector<CaseRecord> records;
  int exit_code = 0;  // 0 when the merged run passes, 1 when not
};

// Throws InputError for a missing or malformed shard output, shards run with a different
// profile or device, or a case present in two shards; InputError for an unwritable OUT_DIR.
// Shards of a sharded run (summary.json "shard": "I/N", N > 1) must all be there, every I from 0
// to N-1, else InputError naming the missing ones; with `allow_missing` the merge goes on and
// their cases (summary.json "selected_cases" less those merged) count as Missing, so the merged
// run is incomplete and does not pass.
MergeResult merge_conformance_outputs(const std::string& out_dir, const std::vector<std::string>& shard_dirs,
                                      bool allow_missing = false);

}  // namespace rastercmp
