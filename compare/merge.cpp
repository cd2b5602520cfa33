#include "compare/merge.hpp"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "compare/conformance.hpp"
#include "compare/expectations.hpp"
#include "compare/report.hpp"
#include "compare/run_outputs.hpp"
#include "compare/run_publish.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

void check_same_run(const RunInfo& first, const RunInfo& other, const std::string& file) {
  if (first.profile != other.profile || first.device != other.device || first.driver != other.driver ||
      first.fma != other.fma)
    throw InputError(file, "$",
                     fmt::format("expected the shards' profile and device ({}, {}); found {}, {}", first.profile,
                                 first.device, other.profile, other.device));
}

// Copies a case's report folder (images, explanations) from a shard's report.
void copy_case_folder(const fs::path& shard_report, const fs::path& out_report, const std::string& case_name) {
  const std::string folder = case_folder(case_name);
  std::error_code ec;
  if (!fs::exists(shard_report / folder, ec)) return;
  fs::create_directories(out_report / folder, ec);
  fs::copy(shard_report / folder, out_report / folder,
           fs::copy_options::recursive | fs::copy_options::overwrite_existing, ec);
  if (ec)
    throw InputError((out_report / folder).string(), "", "could not copy the case's report files: " + ec.message());
}

}  // namespace

MergeResult merge_conformance_outputs(const std::string& out_dir, const std::vector<std::string>& shard_dirs,
                                      bool allow_missing) {
  if (shard_dirs.empty()) throw UsageError("merge: expected at least one shard folder");
  const fs::path out(out_dir);
  ensure_output_dir(out_dir);
  const OutputLock lock(out_dir);  // a conformance or another merge writing there: exit 2 naming it
  ensure_output_dir((out / "report").string());
  MergeResult merged;
  std::map<std::string, std::string> case_origin;
  std::vector<uint32_t> shard_indices;
  for (size_t s = 0; s < shard_dirs.size(); ++s) {
    const fs::path shard(shard_dirs[s]);
    const std::string summary_file = (shard / "summary.json").string();
    ParsedSummary parsed = parse_summary_json(read_text_file(summary_file), summary_file);
    const std::string results_file = (shard / "results.csv").string();
    const auto durations = parse_results_csv(read_text_file(results_file), results_file);
    if (s == 0) merged.info = parsed.info;
    check_same_run(merged.info, parsed.info, summary_file);
    if (parsed.info.shard_count != merged.info.shard_count)
      throw InputError(summary_file, "$.shard",
                       fmt::format("expected shards of one run: {} of {}, and this one of {}", shard_dirs.front(),
                                   merged.info.shard_count, parsed.info.shard_count));
    shard_indices.push_back(parsed.info.shard_index);
    if (s != 0)
      merged.info.not_run.insert(merged.info.not_run.end(), parsed.info.not_run.begin(), parsed.info.not_run.end());
    for (CaseRecord& record : parsed.records) {
      if (!case_origin.emplace(record.name, shard_dirs[s]).second)
        throw InputError(
            summary_file, "$.cases",
            "expected shards over disjoint cases; " + record.name + " is also in " + case_origin[record.name]);
      const auto d = durations.find(record.name);
      if (d != durations.end()) record.duration_s = d->second;
      copy_case_folder(shard / "report", out / "report", record.name);
      merged.records.push_back(std::move(record));
    }
  }
  std::sort(merged.records.begin(), merged.records.end(), [](auto& a, auto& b) { return a.name < b.name; });
  // A sharded run is whole only with every shard: a shard job that uploaded nothing must not let
  // the merge pass. Its cases are unknown by name here, so they count as unnamed Missing.
  if (merged.info.shard_count > 1) {
    std::vector<uint32_t> absent;
    for (uint32_t k = 0; k < merged.info.shard_count; ++k)
      if (std::find(shard_indices.begin(), shard_indices.end(), k) == shard_indices.end()) absent.push_back(k);
    const size_t have = merged.records.size() + merged.info.not_run.size();
    const size_t lacking = merged.info.selected_cases > have ? merged.info.selected_cases - have : 0;
    if (!absent.empty() && !allow_missing)
      throw InputError(
          shard_dirs.front(), "$.shard",
          fmt::format("expected every shard of {} (0 to {}); missing shard(s) {} with {} case(s) "
                      "(merge --allow-missing merges what is there and counts them Missing)",
                      merged.info.shard_count, merged.info.shard_count - 1, fmt::join(absent, ", "), lacking));
    merged.info.missing_unnamed = absent.empty() ? 0 : lacking;
  }
  merged.info.shard_index = 0;
  merged.info.shard_count = 1;
  // A case one folder did not reach may be in another (a resumed run): only the rest is not run.
  std::erase_if(merged.info.not_run, [&](const std::string& name) { return case_origin.count(name) != 0; });
  std::sort(merged.info.not_run.begin(), merged.info.not_run.end());
  merged.info.not_run.erase(std::unique(merged.info.not_run.begin(), merged.info.not_run.end()),
                            merged.info.not_run.end());
  merged.info.interrupted = !merged.info.not_run.empty();
  // A case one shard lacks is Missing; so are the cases of shards not merged.
  merged.info.complete = merged.info.not_run.empty() && merged.info.missing_unnamed == 0;
  write_run_outputs(out_dir, merged.info, merged.records);
  merged.exit_code = run_passed(merged.info, merged.records) ? 0 : 1;
  return merged;
}

}  // namespace rastercmp
