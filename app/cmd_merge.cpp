// rastercmp merge OUT_DIR SHARD_DIR...: joins conformance outputs of shards (compare/merge.hpp).
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "compare/merge.hpp"
#include "model/errors.hpp"

namespace rastercmp::app {
namespace {

struct MergeArgs {
  std::string out_dir;
  std::vector<std::string> shard_dirs;
  bool allow_missing = false;
};

int run_merge(const MergeArgs& args) {
  const MergeResult merged = merge_conformance_outputs(args.out_dir, args.shard_dirs, args.allow_missing);
  fmt::print("merged {} case(s) from {} folder(s)\n", merged.records.size(), args.shard_dirs.size());
  for (const auto& [status, count] : count_statuses(merged.records)) fmt::print("  {:<32} {}\n", status, count);
  if (!merged.info.not_run.empty()) fmt::print("not run: {} case(s)\n", merged.info.not_run.size());
  if (merged.info.missing_unnamed != 0)
    fmt::print("missing: {} case(s) of shards not merged\n", merged.info.missing_unnamed);
  fmt::print("report: {}\n", (std::filesystem::path(args.out_dir) / "report" / "index.html").string());
  fmt::print("result: {}\n", merged.exit_code == 0 ? "pass" : "fail");
  return merged.exit_code == 0 ? kExitOk : kExitMismatch;
}

}  // namespace

void add_merge_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand("merge", "merge the outputs of conformance shards into one folder");
  cmd->add_option("out", args->out_dir, "output folder")->required();
  cmd->add_option("shards", args->shard_dirs, "conformance output folders of the shards")->required();
  cmd->add_flag("--allow-missing", args->allow_missing,
                "merge a sharded run without all its shards; their cases count as Missing (the run does not pass)");
  cmd->callback([args, &exit_code] { exit_code = run_merge(*args); });
}

}  // namespace rastercmp::app
