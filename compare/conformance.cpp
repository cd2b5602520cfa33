#include "compare/conformance.hpp"

#include <fcntl.h>
#include <fmt/core.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <limits>
#include <memory>
#include <regex>

#include "compare/case_children.hpp"
#include "compare/case_judge.hpp"
#include "compare/report.hpp"
#include "compare/run_outputs.hpp"
#include "compare/run_publish.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kLockFile = kOutputLockFile;  // compare/case_select.hpp
constexpr const char* kRetryDir = ".retry";         // below --out: the re-runs' report files, removed after

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::vector<std::string> read_caselist_file(const std::string& file) {
  if (file.empty()) return {};
  std::vector<std::string> names = parse_caselist(read_text_file(file));
  if (names.empty()) throw InputError(file, "", "expected at least one case name");
  return names;
}

std::string progress_line(size_t done, size_t total, const CaseRecord& record, size_t failing, double elapsed_s) {
  const double left_s = elapsed_s / double(done) * double(total - done);
  return fmt::format("[{}/{}] {} {} ({:.2f}s) | ok {}, failing {} | {:.1f}s elapsed, ~{:.1f}s left\n", done, total,
                     record.name, record.status, record.duration_s, done - failing, failing, elapsed_s, left_s);
}

std::string not_run_list(const std::vector<std::string>& names) {
  std::string text = "# cases an interrupted rastercmp conformance run did not reach (use with --caselist)\n";
  for (const std::string& name : names) text += name + "\n";
  return text;
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

// The record of a case that has no render: skipped, crashed, timed out or missing.
CaseRecord record_without_render(const SuiteCase& c, Verdict verdict, const std::string& message) {
  CaseRecord record;
  record.name = c.name;
  record.source = c.path;
  record.width = c.scene.width;
  record.height = c.scene.height;
  record.verdict = verdict;
  record.message = message;
  return record;
}

void judge(CaseRecord& record, const Expectations& expectations) {
  record.expectation = expectations.expected(record.name);
  record.expectation_reason = expectations.reason(record.name);
  const Outcome outcome = judge_outcome(record.name, record.verdict, expectations);
  record.status = outcome.status;
  record.fails_run = outcome.fails_run;
}

// A child's outcome as a judged record of `c`.
CaseRecord record_of(ChildOutcome&& outcome, const SuiteCase& c, const Expectations& expectations) {
  CaseRecord record;
  switch (outcome.end) {
    case ChildEnd::Record: record = std::move(outcome.record); break;
    case ChildEnd::Crash: record = record_without_render(c, Verdict::Crash, outcome.message); break;
    case ChildEnd::Timeout: record = record_without_render(c, Verdict::Timeout, outcome.message); break;
    case ChildEnd::Missing: record = record_without_render(c, Verdict::InternalError, outcome.message); break;
  }
  record.duration_s = outcome.duration_s;
  judge(record, expectations);
  if (outcome.end == ChildEnd::Missing) {
    record.status = "Missing";  // deqp-runner: a case that gave no result
    record.fails_run = true;
  }
  return record;
}

// What the run has so far, written as a whole: records in case order, the rest Missing.
class RunState {
 public:
  RunState(const ConformancePlan& plan, RunInfo info, std::string out_dir)
      : plan_(plan), info_(std::move(info)), out_dir_(std::move(out_dir)), records_(plan.cases.size()) {}

  void set(size_t i, CaseRecord record) { records_[i] = std::move(record); }
  const std::optional<CaseRecord>& at(size_t i) const { return records_[i]; }
  RunInfo& info() { return info_; }

  std::vector<CaseRecord> finished() const {
    std::vector<CaseRecord> out;
    for (const auto& r : records_)
      if (r) out.push_back(*r);
    return out;
  }

  void publish() {
    info_.not_run.clear();
    for (size_t i = 0; i < records_.size(); ++i)
      if (!records_[i]) info_.not_run.push_back(plan_.cases[i].name);
    write_run_outputs(out_dir_, info_, finished());
  }

 private:
  const ConformancePlan& plan_;
  RunInfo info_;
  std::string out_dir_;
  std::vector<std::optional<CaseRecord>> records_;
};

size_t batch_size_for(size_t cases, unsigned jobs) {
  // Enough batches to keep every job busy near the end; few enough that start-up (about 0.5 s a
  // process) stays small beside the cases.
  const size_t batches = size_t(std::max(1u, jobs)) * 4;  // size_t: no wrap for any --jobs
  const size_t per_job = (cases + batches - 1) / batches;
  return std::clamp<size_t>(per_job, 1, 16);
}

}  // namespace

RunInfo run_info_for(const CaseRunner& runner) {
  RunInfo info;
  info.profile = runner.profile_name();
  const CpuOptions options = runner.cpu_options(Scene{});
  if (runner.profile() == CompareProfile::Lavapipe && options.lavapipe_from_driver)
    info.profile_warning = runner.lavapipe_choice().warning;
  info.device = runner.device().name;
  info.driver = runner.device().driver_info;
  info.fma = runner.cpu_options(Scene{}).fma;
  return info;
}

OutputLock::OutputLock(const std::string& out_dir) {
  const std::string path = (fs::path(out_dir) / kLockFile).string();
  fd_ = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(path, "", "expected a lock file that can be created");
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    char pid[32] = {};
    const ssize_t n = pread(fd_, pid, sizeof pid - 1, 0);
    close(fd_);
    fd_ = -1;
    std::string holder(pid, size_t(std::max<ssize_t>(n, 0)));
    holder.erase(holder.find_last_not_of(" \n") + 1);
    throw UsageError(fmt::format(
        "--out {}: another rastercmp run (conformance, merge or capture; pid {}) is writing there; wait for it "
        "or choose another folder",
        out_dir, holder.empty() ? "unknown" : holder));
  }
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd_, 0) != 0 || pwrite(fd_, pid.data(), pid.size(), 0) != ssize_t(pid.size()))
    throw InputError(path, "", "could not write the lock file");
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  // Emptied, then released: the file stays (another run may hold it next), naming no one, so a
  // finished run's folder is the same whoever ran it.
  if (ftruncate(fd_, 0) != 0) {
  }
  close(fd_);
}

size_t remove_previous_verdict(const std::string& out_dir) {
  size_t removed = 0;
  std::error_code ec;
  for (const char* name : {"summary.json", "results.csv", "failures.csv", "junit.xml", "not_run.txt"})
    removed += fs::remove(fs::path(out_dir) / name, ec) ? 1 : 0;
  return removed;
}

bool writer_gone(long long pid) {
  if (pid <= 0 || pid > std::numeric_limits<pid_t>::max()) return true;
  return ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
}

size_t remove_stale_temporaries(const std::string& out_dir) {
  // model/image_io.cpp and compare/report_images.cpp name them ".STEM.tmpPID.EXT", in the folders
  // a run writes: --out itself, report/ and each case's report/cases/<case>/. Only those folders,
  // and only a temporary whose writer is gone: a file of that shape elsewhere below --out is
  // someone else's, and a live process (a render into the same folder) still writes its own.
  static const std::regex temporary(R"(\..*\.tmp([0-9]{1,10})(\.[A-Za-z0-9]+)?)");
  size_t removed = 0;
  std::error_code ec;
  removed += fs::remove_all(fs::path(out_dir) / kRetryDir, ec) > 0 ? 1 : 0;
  std::vector<fs::path> folders = {fs::path(out_dir), fs::path(out_dir) / "report"};
  for (auto it = fs::directory_iterator(fs::path(out_dir) / "report" / "cases", ec);
       !ec && it != fs::directory_iterator(); it.increment(ec))
    if (it->is_directory(ec) && !it->is_symlink(ec)) folders.push_back(it->path());
  std::vector<fs::path> stale;
  for (const fs::path& folder : folders) {
    std::error_code walk;
    for (auto it = fs::directory_iterator(folder, walk); !walk && it != fs::directory_iterator(); it.increment(walk)) {
      std::smatch m;
      const std::string name = it->path().filename().string();
      if (it->is_regular_file(walk) && !it->is_symlink(walk) && std::regex_match(name, m, temporary) &&
          writer_gone(std::stoll(m[1].str())))
        stale.push_back(it->path());
    }
  }
  for (const fs::path& p : stale) removed += fs::remove(p, ec) ? 1 : 0;
  return removed;
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
  const CaseFilter filter{read_caselist_file(o.caselist_file), o.case_globs, {}};
  std::vector<SuiteCase> selected = select_cases(std::move(suite), filter, o.caselist_file);
  if (selected.empty())
    throw UsageError(fmt::format("no case of the suite {} is left after --caselist and --case", suite_dir));
  plan.selected_cases = selected.size();
  plan.cases = take_shard(std::move(selected), plan.shard);
  for (const SuiteCase& c : plan.cases) {
    const auto skip = std::find_if(plan.expectations.skips.begin(), plan.expectations.skips.end(),
                                   [&](const Pattern& p) { return std::regex_search(c.name, p.regex); });
    plan.skipped_by.push_back(skip == plan.expectations.skips.end() ? "" : skip->text);
  }
  return plan;
}

ConformanceResult run_conformance(const ConformanceOptions& options, const ConformancePlan& plan,
                                  const std::atomic<int>& stop_signal, const ProgressFn& progress) {
  const fs::path out(options.out_dir);
  RunInfo info;
  {
    // The device the children will use, named once (and no Vulkan: EnvironmentError, exit 3).
    // With --captures, the device their render.json names (and no Vulkan needed).
    const std::unique_ptr<CaseRunner> runner = make_runner(options, plan);
    info = run_info_for(*runner);
  }
  info.shard_index = plan.shard.index;
  info.shard_count = plan.shard.count;
  info.selected_cases = plan.selected_cases;
  std::error_code ec;
  fs::remove(out / "not_run.txt", ec);  // from an earlier run into the same folder
  RunState state(plan, info, options.out_dir);
  state.publish();

  const Clock::time_point run_start = Clock::now();
  size_t done = 0, failing = 0;
  const auto finish = [&](size_t i, CaseRecord record) {
    ++done;
    failing += record.fails_run ? 1 : 0;
    state.set(i, std::move(record));
    state.publish();
    if (progress) progress(progress_line(done, plan.cases.size(), *state.at(i), failing, seconds_since(run_start)));
  };

  std::vector<ChildCase> to_run;
  for (size_t i = 0; i < plan.cases.size(); ++i) {
    if (plan.skipped_by[i].empty()) {
      to_run.push_back({i, plan.cases[i].path});
      continue;
    }
    CaseRecord skipped = record_without_render(plan.cases[i], Verdict::NotSupported,
                                               "skipped: the name matches the --skips pattern " + plan.skipped_by[i]);
    judge(skipped, Expectations{});
    skipped.expectation = plan.expectations.expected(skipped.name);
    finish(i, std::move(skipped));
  }

  const ChildRunOptions child_options{options.worker_command, (out / "report").string(), options.jobs,
                                      options.timeout_s, batch_size_for(to_run.size(), options.jobs)};
  run_in_children(child_options, to_run, stop_signal, [&](ChildOutcome&& outcome) {
    const size_t i = outcome.id;
    finish(i, record_of(std::move(outcome), plan.cases[i], plan.expectations));
  });

  // Re-run what fails the run, each case alone in a fresh process, its report files set aside:
  // a case whose re-run passes is a Flake (deqp-runner), and keeps its first record.
  const fs::path retry_dir = out / kRetryDir;
  for (unsigned round = 0; round < options.flake_retries && stop_signal.load() == 0; ++round) {
    std::vector<ChildCase> again;
    for (size_t i = 0; i < plan.cases.size(); ++i)
      if (state.at(i) && state.at(i)->fails_run && plan.skipped_by[i].empty()) again.push_back({i, plan.cases[i].path});
    if (again.empty()) break;
    ensure_output_dir(retry_dir.string());
    ChildRunOptions retry_options = child_options;
    retry_options.report_dir = retry_dir.string();
    retry_options.batch_size = 1;
    run_in_children(retry_options, again, stop_signal, [&](ChildOutcome&& outcome) {
      const size_t i = outcome.id;
      const CaseRecord retried = record_of(std::move(outcome), plan.cases[i], plan.expectations);
      CaseRecord record = *state.at(i);
      if (retried.status == record.status) return;
      record.message += fmt::format(" [re-run {}: {} ({})]", round + 1, retried.status, retried.message);
      // A Flake failed, then passed: a re-run that fails another way (Timeout after Crash) leaves
      // the case failing the run, with both reasons.
      if (!retried.fails_run) {
        record.status = "Flake";
        record.fails_run = false;
      }
      state.set(i, std::move(record));
      state.publish();
    });
  }
  fs::remove_all(retry_dir, ec);

  RunInfo& final_info = state.info();
  // A stop that came when every case already had its result (during the last case, which the
  // child finishes, or during the re-runs) leaves nothing to resume: the run is complete, its
  // failing cases keep failing (a re-run cut short makes no Flake), and its exit is the verdict's.
  if (stop_signal.load() != 0 && !final_info.not_run.empty()) {
    final_info.interrupted = true;
    state.publish();
    write_text_file_atomic((out / "not_run.txt").string(), not_run_list(final_info.not_run));
  } else {
    final_info.complete = true;
  }
  state.publish();
  ConformanceResult result;
  result.records = state.finished();
  result.info = final_info;
  result.exit_code = final_info.interrupted ? 128 + stop_signal.load() : run_passed(final_info, result.records) ? 0 : 1;
  return result;
}

void print_conformance_summary(std::FILE* out, const ConformanceResult& result, const std::string& out_dir,
                               const std::string& resume_hint) {
  const auto& records = result.records;
  fmt::print(out, "\n{} case(s) run on {} ({}; {} profile)\n", records.size(), result.info.device, result.info.driver,
             result.info.profile);
  if (!result.info.profile_warning.empty()) fmt::print(out, "warning: {}\n", result.info.profile_warning);
  auto statuses = count_statuses(records);
  if (!result.info.not_run.empty()) statuses["Missing"] += result.info.not_run.size();
  for (const auto& [status, count] : statuses) fmt::print(out, "  {:<32} {}\n", status, count);
  std::vector<const CaseRecord*> slowest;
  for (const CaseRecord& c : records) slowest.push_back(&c);
  std::stable_sort(slowest.begin(), slowest.end(), [](auto* a, auto* b) { return a->duration_s > b->duration_s; });
  if (slowest.size() > 5) slowest.resize(5);
  if (!slowest.empty()) fmt::print(out, "slowest:\n");
  for (const CaseRecord* c : slowest) fmt::print(out, "  {:8.3f}s  {}\n", c->duration_s, c->name);
  std::vector<const CaseRecord*> unexpected;
  for (const CaseRecord& c : records)
    if (c.fails_run || c.status == "Flake") unexpected.push_back(&c);
  if (!unexpected.empty()) fmt::print(out, "unexpected results and flakes:\n");
  for (const CaseRecord* c : unexpected) fmt::print(out, "  {},{}\n", c->name, c->status);
  const fs::path dir(out_dir);
  fmt::print(out, "report: {}\n", (dir / "report" / "index.html").string());
  if (result.info.interrupted)
    fmt::print(out, "interrupted: {} case(s) not run, listed in {}.\n{}", result.info.not_run.size(),
               (dir / "not_run.txt").string(), resume_hint);
  fmt::print(out, "result: {}\n", result.info.interrupted ? "interrupted" : result.exit_code == 0 ? "pass" : "fail");
}

}  // namespace rastercmp
