// `rastercmp bench --scaling --model --tasks N`: each queue phase's tasks and the serial time's
// parts at N workers, printed after the table and in the JSON (app/bench_model.cpp; the fast path
// alone: no Vulkan device); `rastercmp bench --json`: each scene's target beside its times; the
// timed charts keep freed memory as the bench does.
#include <gtest/gtest.h>
#include <sched.h>

#include <algorithm>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

TEST(CliBench, ModelListsEachQueuePhasesTasksAtTheWorkersAsked) {
  const TempDir tmp;
  const RunResult r = run_cli({"bench", "--scaling", "--model", "--reps", "1", "--scene", "perspective", "--tasks",
                               "16", "--json", (tmp / "model.json").string(), "--chart-dir", (tmp / "chart").string()});
  ASSERT_EQ(r.exit_code, 0) << describe({"bench"}, r);
  ASSERT_NE(r.out.find("queue phases' tasks at 16 workers"), std::string::npos) << r.out;
  // printed: "<scene> at 16 workers, <phase>: <n> tasks, ..." for each queue phase
  std::map<std::string, size_t> printed;
  const std::regex line(R"(^bench\.perspective at 16 workers, ([a-z ]+): (\d+) tasks, )");
  for (const std::string& l : lines_of(r.out)) {
    std::smatch m;
    if (std::regex_search(l, m, line)) printed[m[1]] = std::stoul(m[2]);
  }
  for (const char* phase : {"vertices", "block rows", "bands"})
    EXPECT_TRUE(printed.count(phase)) << phase << "\n" << r.out;
  ASSERT_NE(r.out.find("the calling thread's serial time at 16 workers"), std::string::npos) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(bench\.perspective at 16 workers, serial [0-9.]+ us: [0-9.]+ )"
                                                  R"(before vertices, .* [0-9.]+ before bands, [0-9.]+ after the )"
                                                  R"(last phase)")))
      << r.out;
  // the page faults of the profiled renders (their profiles kept out of the renders' heap)
  EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(\nperspective: \d+ in the first rep's profiled renders, \d+ in )"
                                                  R"(the 0 other reps')")))
      << r.out;
  const nlohmann::json j = nlohmann::json::parse(read_file(tmp / "model.json"));
  EXPECT_GE(j["scenes"][0]["page_faults_profiled"]["first_rep"].get<long>(), 0);
  EXPECT_EQ(j["scenes"][0]["page_faults_profiled"]["other_reps"].get<long>(), 0) << "one rep";
  size_t with_tasks = 0;
  const uint32_t cores = j["usable_cpus"];
  EXPECT_GE(cores, 1u);
  EXPECT_LE(cores, j["hardware_threads"].get<uint32_t>());
  for (const nlohmann::json& point : j["scenes"][0]["workers"]) {
    // the measured wall time (unprofiled renders) where N <= the CPUs it may use, else none
    if (point["workers"].get<uint32_t>() <= cores)
      EXPECT_GT(point["measured_wall_seconds"].get<double>(), 0.0) << point["workers"];
    else
      EXPECT_TRUE(point["measured_wall_seconds"].is_null()) << point["workers"];
    if (point["workers"] != 16) {
      EXPECT_FALSE(point.contains("tasks")) << point["workers"];
      continue;
    }
    ++with_tasks;
    ASSERT_EQ(point["tasks"].size(), printed.size());
    for (const nlohmann::json& phase : point["tasks"]) {
      const std::string name = phase["phase"];
      ASSERT_EQ(phase["tasks"].size(), printed[name]) << name;
      double largest = 0;
      for (const nlohmann::json& task : phase["tasks"]) {
        EXPECT_GE(task["seconds"].get<double>(), 0.0) << name;
        EXPECT_LT(task["worker"].get<uint32_t>(), 16u) << name;
        largest = std::max(largest, task["seconds"].get<double>());
      }
      // list scheduling hands each task to a worker: the phase takes at least its largest task
      EXPECT_GE(phase["projected_seconds"].get<double>(), largest) << name;
    }
    // the serial time's parts: one per phase in the order they ran, the vertices first and the
    // bands last, and the rest after the last phase
    ASSERT_EQ(point["serial_parts"].size(), 1u);
    const nlohmann::json& serial = point["serial_parts"][0];
    EXPECT_EQ(serial["scene"], "bench.perspective");
    std::vector<std::string> phases;
    double parts = serial["after_last_phase_seconds"].get<double>();
    EXPECT_GE(parts, 0.0);
    for (const nlohmann::json& before : serial["before_phases"]) {
      phases.push_back(before["phase"]);
      EXPECT_GE(before["seconds"].get<double>(), 0.0) << phases.back();
      parts += before["seconds"].get<double>();
    }
    ASSERT_GE(phases.size(), 3u);
    EXPECT_EQ(phases.front(), "vertices");
    EXPECT_EQ(phases.back(), "bands");
    for (const auto& [name, count] : printed)
      EXPECT_NE(std::find(phases.begin(), phases.end(), name), phases.end()) << name;
    // each part is the median of its reps' (one rep here): they add up to the serial time
    EXPECT_NEAR(parts, serial["serial_seconds"].get<double>(), 1e-9);
  }
  EXPECT_EQ(with_tasks, 1u);
}

// Confined to one CPU (as `taskset -c 0` confines it; the affinity mask is inherited), the model
// projects every N from that CPU and times only N = 1, and --scaling times only 1 thread: a
// render of N workers taking turns on one core is no measurement of N cores.
TEST(CliBench, ScalingMeasuresNoMoreWorkersThanTheCpusItMayUse) {
  cpu_set_t before;
  CPU_ZERO(&before);
  ASSERT_EQ(sched_getaffinity(0, sizeof(before), &before), 0);
  int first = 0;
  while (!CPU_ISSET(first, &before)) ++first;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof(one), &one), 0);
  const TempDir tmp;
  const RunResult model = run_cli({"bench", "--scaling", "--model", "--reps", "1", "--scene", "fill_f2b", "--json",
                                   (tmp / "model.json").string(), "--chart-dir", (tmp / "chart").string()});
  const RunResult scaling = run_cli({"bench", "--scaling", "--reps", "1", "--scene", "fill_f2b", "--json",
                                     (tmp / "scaling.json").string(), "--chart-dir", (tmp / "chart").string()});
  ASSERT_EQ(sched_setaffinity(0, sizeof(before), &before), 0);
  ASSERT_EQ(model.exit_code, 0) << describe({"bench", "--scaling", "--model"}, model);
  ASSERT_EQ(scaling.exit_code, 0) << describe({"bench", "--scaling"}, scaling);
  EXPECT_NE(model.out.find(" usable), fast path kernels"), std::string::npos) << model.out;
  const nlohmann::json m = nlohmann::json::parse(read_file(tmp / "model.json"));
  EXPECT_EQ(m["usable_cpus"], 1);
  ASSERT_EQ(m["scenes"].size(), 1u);
  for (const nlohmann::json& point : m["scenes"][0]["workers"]) {
    EXPECT_GT(point["projected_seconds"].get<double>(), 0.0) << point["workers"];
    if (point["workers"] == 1)
      EXPECT_GT(point["measured_wall_seconds"].get<double>(), 0.0);
    else
      EXPECT_TRUE(point["measured_wall_seconds"].is_null()) << point["workers"];
  }
  const nlohmann::json s = nlohmann::json::parse(read_file(tmp / "scaling.json"));
  EXPECT_EQ(s["usable_cpus"], 1);
  ASSERT_EQ(s["scenes"].size(), 1u);
  ASSERT_EQ(s["scenes"][0]["threads"].size(), 1u);
  EXPECT_EQ(s["scenes"][0]["threads"][0]["threads"], 1);
}

// The bench's JSON carries each scene's target (kTargets), the one its printed verdict reads.
TEST(CliBench, JsonCarriesEachScenesTarget) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const RunResult r = run_cli(
      {"bench", "--reps", "1", "--exact-reps", "1", "--scene", "fill_f2b", "--json", (tmp / "bench.json").string()});
  ASSERT_EQ(r.exit_code, 0) << describe({"bench"}, r);
  const std::regex verdict(R"(target fill_f2b +lavapipe/fast +[0-9.]+x +must reach +([0-9]+)x: .* aim +([0-9]+)x)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, verdict)) << r.out;
  const nlohmann::json j = nlohmann::json::parse(read_file(tmp / "bench.json"));
  ASSERT_EQ(j["scenes"].size(), 1u);
  EXPECT_EQ(j["scenes"][0]["name"], "fill_f2b");
  EXPECT_EQ(j["scenes"][0]["target"]["must"].get<double>(), std::stod(m[1]));
  EXPECT_EQ(j["scenes"][0]["target"]["aim"].get<double>(), std::stod(m[2]));
}

// `rastercmp chart scene-needs` times its renders as the bench does, with the memory a render
// frees kept for the next (bench::keep_freed_memory), and records it; ASan's allocator refuses it.
TEST(CliBench, TimedChartsKeepFreedMemoryAndSaySo) {
  const TempDir tmp;
  const RunResult r = run_cli({"chart", "scene-needs", "--quick", "--out", (tmp / "needs").string()});
  ASSERT_EQ(r.exit_code, 0) << describe({"chart"}, r);
  const nlohmann::json j = nlohmann::json::parse(read_file(tmp / "needs" / "scene_needs.json"));
  ASSERT_TRUE(j.contains("freed_memory_kept")) << j.dump();
#ifdef RASTERCMP_SANITIZER_BUILD
  EXPECT_FALSE(j["freed_memory_kept"].get<bool>());
#else
  EXPECT_TRUE(j["freed_memory_kept"].get<bool>());
#endif
}

}  // namespace
}  // namespace rastercmp::cli_test
