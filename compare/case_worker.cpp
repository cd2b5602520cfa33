#include "compare/case_worker.hpp"

#include <fmt/core.h>
#include <sys/prctl.h>
#include <unistd.h>
#include <algorithm>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "compare/case_judge.hpp"
#include "compare/explain_text.hpp"
#include "compare/report.hpp"
#include "model/errors.hpp"
#include "model/mesh_import.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

// The test-only fault named for `case_name` in RASTERCMP_TEST_CASE_FAULT, or "".
std::string injected_fault(const std::string& case_name) {
  const char* value = std::getenv("RASTERCMP_TEST_CASE_FAULT");
  if (value == nullptr || *value == '\0') return "";
  std::string_view rest(value);
  std::string found;
  while (!rest.empty()) {
    const auto end = rest.find(';');
    const std::string_view entry = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view{} : rest.substr(end + 1);
    const auto colon = entry.find(':');
    const std::string_view kind = entry.substr(0, colon);
    constexpr std::string_view kKinds[] = {"crash", "hang",       "fail_once", "crash_then_fail",
                                           "exit2", "stray_line", "helper",    "close_fds_hang"};
    if (colon == std::string_view::npos || std::find(std::begin(kKinds), std::end(kKinds), kind) == std::end(kKinds))
      throw std::invalid_argument(
          "RASTERCMP_TEST_CASE_FAULT: expected KIND:CASE with KIND crash, hang, fail_once, crash_then_fail, exit2, "
          "stray_line, helper or close_fds_hang, found \"" +
          std::string(entry) + "\"");
    if (entry.substr(colon + 1) == case_name) found = std::string(kind);
  }
  return found;
}

// Whether a fail_once or crash_then_fail fault is met for the first time: it leaves a file behind.
bool first_time(const std::string& case_name) {
  const char* dir = std::getenv("RASTERCMP_TEST_FAULT_DIR");
  if (dir == nullptr || *dir == '\0')
    throw std::invalid_argument("RASTERCMP_TEST_CASE_FAULT fail_once: expected RASTERCMP_TEST_FAULT_DIR");
  const fs::path marker = fs::path(dir) / case_name;
  if (fs::exists(marker)) return false;
  std::ofstream(marker) << "failed once\n";
  return true;
}

// A helper process, as a driver's crash handler or cache daemon: it inherits stdout, stderr and the
// result pipe and sleeps for ever; its pid goes to RASTERCMP_TEST_FAULT_DIR/CASE.helper.
void start_helper(const std::string& case_name) {
  const char* dir = std::getenv("RASTERCMP_TEST_FAULT_DIR");
  if (dir == nullptr || *dir == '\0')
    throw std::invalid_argument("RASTERCMP_TEST_CASE_FAULT helper: expected RASTERCMP_TEST_FAULT_DIR");
  const pid_t helper = fork();
  if (helper == 0)
    for (;;) pause();
  std::ofstream(fs::path(dir) / (case_name + ".helper")) << helper << "\n";
}

void write_all(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw InputError("(result pipe)", "", std::string("could not write to the parent: ") + std::strerror(errno));
    done += size_t(n);
  }
}

}  // namespace

int run_case_worker(const WorkerOptions& o, const std::atomic<int>& stop) {
  std::signal(SIGPIPE, SIG_IGN);  // a parent gone is a write error, not a silent death
  // A parent killed outright (kill -9) takes its children with it: none keeps writing into --out.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  const bool from_captures = !o.captures_root.empty();
  const std::unique_ptr<CaseRunner> runner_ptr =
      from_captures ? std::make_unique<CaseRunner>(o.profile, o.cpu_options, DeviceInfo{})
                    : std::make_unique<CaseRunner>(o.profile, o.cpu_options, o.vk);
  CaseRunner& runner = *runner_ptr;
  for (size_t i = 0; i < o.scene_files.size() && stop.load() == 0; ++i) {
    const Scene scene = load_scene_or_model(o.scene_files[i]);
    write_all(o.result_fd, fmt::format("begin\t{}\n", i));
    const auto start = std::chrono::steady_clock::now();
    const std::string fault = injected_fault(scene.name);
    if (!fault.empty()) {
      fmt::print(stderr, "test-only fault: {} in {}\n", fault, scene.name);
      std::fflush(stderr);
    }
    // crash_then_fail: a crash the first time, a plain failure after it (never a pass).
    const bool crash_now = fault == "crash" || (fault == "crash_then_fail" && first_time(scene.name));
    if (crash_now) {  // a plain SIGSEGV death, also where a sanitizer has its own handler
      std::signal(SIGSEGV, SIG_DFL);
      std::raise(SIGSEGV);
    }
    while (fault == "hang") std::this_thread::sleep_for(std::chrono::seconds(1));
    if (fault == "exit2") std::_Exit(2);  // a driver that exits with the code of bad input
    if (fault == "stray_line") write_all(o.result_fd, "a driver's line\n");  // into the result pipe
    if (fault == "helper") start_helper(scene.name);
    if (fault == "close_fds_hang") {  // both pipes reach end of file, the process lives on
      for (int fd = 0; fd < 1024; ++fd) close(fd);
      for (;;) pause();
    }
    CaseResult result = from_captures
                            ? runner.run_capture(scene, capture_dir_for(o.captures_root, o.suite_dir, o.scene_files[i]))
                            : runner.run(scene);
    if ((fault == "fail_once" && first_time(scene.name)) || fault == "crash_then_fail") {
      result.verdict = Verdict::Fail;
      result.message = "test-only injected failure (RASTERCMP_TEST_CASE_FAULT " + fault + ")";
    }
    const SuiteCase suite_case{scene.name, o.scene_files[i], scene};
    CaseRecord record = make_case_record(suite_case, result, Expectations{});
    record.images = write_case_images(o.report_dir, scene.name, result);
    record.explains =
        write_case_explanations(o.report_dir, scene.name, scene, runner.cpu_options(scene), result, runner.profile());
    record.duration_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::ordered_json j = case_to_json(record, true);
    j["duration_s"] = record.duration_s;
    write_all(o.result_fd, fmt::format("record\t{}\t{}\n", i, j.dump()));
  }
  return 0;
}

}  // namespace rastercmp
