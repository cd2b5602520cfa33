#include "compare/conformance.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>

#include "compare/case_judge.hpp"
#include "compare/explain_text.hpp"
#include "compare/report.hpp"
#include "compare/run_outputs.hpp"
#include "compare/run_publish.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::vector<std::string> read_caselist_file(const std::string& file) {
  if (file.empty()) return {};
  std::vector<std::string> names = parse_caselist(read_text_file(file));
  if (names.empty()) throw InputError(file, "", "expected at least one case name");
  return names;
}

std::string progress_line(size_t done, size_t total, const CaseRecord& record, const std::vector<CaseRecord>& records,
                          double elapsed_s) {
  const size_t failing = size_t(std::count_if(records.begin(), records.end(), [](auto& c) { return c.fails_run; }));
  const double left_s = elapsed_s / double(done) * double(total - done);
  return fmt::format("[{}/{}] {} {} ({:.2f}s) | ok {}, failing {} | {:.1f}s elapsed, ~{:.1f}s left\n", done, total,
                     record.name, record.status, record.duration_s, records.size() - failing, failing, elapsed_s,
                     left_s);
}

std::string not_run_list(const std::vector<std::string>& names) {
  std::string text = "# cases an interrupted rastercmp conformance run did not reach (use with --caselist)\n";
  for (const std::string& name : names) text += name + "\n";
  return text;
}

// Renders, judges and reports one case; the record carries its duration.
CaseRecord run_one_case(CaseRunner& runner, const SuiteCase& suite_case, const Expectations& expectations,
                        const std::string& report_dir, const std::string& capture_dir) {
  const Clock::time_point start = Clock::now();
  const CaseResult result =
      capture_dir.empty() ? runner.run(suite_case.scene) : runner.run_capture(suite_case.scene, capture_dir);
  CaseRecord record = make_case_record(suite_case, result, expectations);
  record.images = write_case_images(report_dir, suite_case.name, result);
  record.explains = write_case_explanations(report_dir, suite_case.name, suite_case.scene,
                                            runner.cpu_options(suite_case.scene), result, runner.profile());
  record.duration_s = seconds_since(start);
  return record;
}

// The device the captures name: the first case's readable render.json.
DeviceInfo captured_device(const ConformanceOptions& o, const ConformancePlan& plan) {
  for (const SuiteCase& c : plan.cases) {
    try {
      return capture_device(capture_dir_for(o.captures_root, plan.suite_dir, c.path));
    } catch (const InputError&) {
      // a missing or broken capture is that case's ResourceError; the device comes from another
    }
  }
  throw InputError(o.captures_root, "",
                   "expected the captures of the suite's cases (rastercmp capture --out); none of the selected "
                   "cases has a readable render.json there");
}

std::unique_ptr<CaseRunner> make_runner(const ConformanceOptions& o, const ConformancePlan& plan) {
  if (o.captures_root.empty()) return std::make_unique<CaseRunner>(o.profile, o.cpu_options, o.vk);
  return std::make_unique<CaseRunner>(o.profile, o.cpu_options, captured_device(o, plan));
}

}  // namespace

RunInfo run_info_for(const CaseRunner& runner) {
  RunInfo info;
  info.profile = to_string(runner.profile());
  info.device = runner.device().name;
  info.driver = runner.device().driver_info;
  info.fma = runner.cpu_options(Scene{}).fma;
  return info;
}

ConformancePlan plan_conformance(const ConformanceOptions& o) {
  if (o.out_dir.empty()) throw UsageError("--out: expected an output folder");
  ensure_output_dir(o.out_dir);  // before any work: an unwritable folder is a usage error
  ensure_output_dir((fs::path(o.out_dir) / "report").string());
  ConformancePlan plan;
  plan.expectations = load_expectations(o.baseline_file, o.flakes_file, o.skips_file);
  plan.shard = o.shard ? *o.shard : shard_from_environment().value_or(Shard{});
  const std::string suite_dir = o.suite_dir.empty() ? default_suite_dir() : o.suite_dir;
  plan.suite_dir = suite_dir;
  std::vector<SuiteCase> suite = load_suite(suite_dir);
  plan.suite_size = suite.size();
  const CaseFilter filter{read_caselist_file(o.caselist_file), o.case_globs, plan.expectations.skips};
  std::vector<SuiteCase> selected = select_cases(std::move(suite), filter, o.caselist_file);
  if (selected.empty())
    throw UsageError(fmt::format("no case of the suite {} is left after --caselist, --case and --skips", suite_dir));
  plan.cases = take_shard(std::move(selected), plan.shard);
  return plan;
}

ConformanceResult run_conformance(const ConformanceOptions& options, const ConformancePlan& plan,
                                  const std::atomic<bool>& stop, const ProgressFn& progress) {
  const std::unique_ptr<CaseRunner> runner_ptr = make_runner(options, plan);
  CaseRunner& runner = *runner_ptr;
  const fs::path out(options.out_dir);
  const std::string report_dir = (out / "report").string();
  ConformanceResult result;
  RunInfo& info = result.info;
  info = run_info_for(runner);
  std::error_code ec;
  fs::remove(out / "not_run.txt", ec);  // from an earlier run into the same folder
  ResultsCsvWriter results_csv((out / "results.csv").string());
  write_run_outputs(options.out_dir, info, result.records);

  const Clock::time_point run_start = Clock::now();
  for (size_t i = 0; i < plan.cases.size(); ++i) {
    if (stop.load()) {
      info.interrupted = true;
      for (size_t j = i; j < plan.cases.size(); ++j) info.not_run.push_back(plan.cases[j].name);
      break;
    }
    const std::string capture_dir =
        options.captures_root.empty() ? "" : capture_dir_for(options.captures_root, plan.suite_dir, plan.cases[i].path);
    CaseRecord record = run_one_case(runner, plan.cases[i], plan.expectations, report_dir, capture_dir);
    results_csv.append(record);
    result.records.push_back(std::move(record));
    write_run_outputs(options.out_dir, info, result.records);
    if (progress)
      progress(
          progress_line(i + 1, plan.cases.size(), result.records.back(), result.records, seconds_since(run_start)));
  }
  if (info.interrupted) {
    write_text_file_atomic((out / "not_run.txt").string(), not_run_list(info.not_run));
    write_run_outputs(options.out_dir, info, result.records);
  }
  result.exit_code = info.interrupted ? kExitInterrupted : run_passed(info, result.records) ? 0 : 1;
  return result;
}

void print_conformance_summary(std::FILE* out, const ConformanceResult& result, const std::string& out_dir) {
  const auto& records = result.records;
  fmt::print(out, "\n{} case(s) run on {} ({} profile)\n", records.size(), result.info.device, result.info.profile);
  for (const auto& [status, count] : count_statuses(records)) fmt::print(out, "  {:<32} {}\n", status, count);
  std::vector<const CaseRecord*> slowest;
  for (const CaseRecord& c : records) slowest.push_back(&c);
  std::stable_sort(slowest.begin(), slowest.end(), [](auto* a, auto* b) { return a->duration_s > b->duration_s; });
  if (slowest.size() > 5) slowest.resize(5);
  if (!slowest.empty()) fmt::print(out, "slowest:\n");
  for (const CaseRecord* c : slowest) fmt::print(out, "  {:8.3f}s  {}\n", c->duration_s, c->name);
  const fs::path dir(out_dir);
  fmt::print(out, "report: {}\n", (dir / "report" / "index.html").string());
  if (result.info.interrupted) {
    fmt::print(out,
               "interrupted: {} case(s) not run, listed in {}.\nresume: run the same command without --shard (and "
               "without GTEST_SHARD_*), with --caselist {} --out NEW_DIR; then: rastercmp merge MERGED_DIR {} "
               "NEW_DIR\n",
               result.info.not_run.size(), (dir / "not_run.txt").string(), (dir / "not_run.txt").string(), out_dir);
  }
  fmt::print(out, "result: {}\n", result.info.interrupted ? "interrupted" : result.exit_code == 0 ? "pass" : "fail");
}

}  // namespace rastercmp
