// `rastercmp bench --scaling --model --tasks N`: each queue phase's tasks at N workers, printed
// after the table and in the JSON (app/cmd_bench.cpp). The fast path alone: no Vulkan device.
#include <gtest/gtest.h>

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
  const nlohmann::json j = nlohmann::json::parse(read_file(tmp / "model.json"));
  size_t with_tasks = 0;
  for (const nlohmann::json& point : j["scenes"][0]["workers"]) {
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
  }
  EXPECT_EQ(with_tasks, 1u);
}

}  // namespace
}  // namespace rastercmp::cli_test
