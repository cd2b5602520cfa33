// `chart speed-accuracy`'s fronts, separation marks, run metadata and scenes, on synthetic
// EntrySummary values (no device): the fronts are computed within the scalar tier, so a family
// with several scalar methods that trade time for accuracy shows more than one point.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cpu_raster/cpu_raster.hpp"
#include "experiments/speed_accuracy.hpp"
#include "model/host.hpp"

namespace rastercmp::experiments {
namespace {

EntrySummary entry(const std::string& family, const std::string& method, double ms, double coverage, double low_ms,
                   double high_ms, Tier tier = Tier::Scalar) {
  EntrySummary e;
  e.family = family;
  e.method = method;
  e.seconds_per_frame = ms * 1e-3;
  e.coverage_mismatch_pct = coverage;
  e.depth_mismatch_pct = coverage;
  e.seconds_low = low_ms * 1e-3;
  e.seconds_high = high_ms * 1e-3;
  e.tier = tier;
  return e;
}

// exact 4 ms exact; fill methods faster and rougher; the fast path faster than all and exact.
std::vector<EntrySummary> fill_family() {
  return {entry("exact path", "exact", 4.0, 0.0, 3.8, 4.2),
          entry("fast path", "threads=2", 0.5, 0.0, 0.45, 0.55, Tier::Fast),
          entry("fill", "quick", 2.0, 0.5, 1.9, 2.1),
          entry("fill", "middle", 3.0, 0.1, 2.9, 3.1),
          entry("fill", "slow and wrong", 5.0, 0.9, 4.9, 5.1),
          entry("line", "dda", 1.0, 3.0, 0.9, 1.1)};
}

std::vector<size_t> entries_of(const std::vector<FrontPoint>& front) {
  std::vector<size_t> out;
  for (const FrontPoint& p : front) out.push_back(p.entry);
  return out;
}

TEST(SpeedAccuracyFront, ScalarTierFrontHasEveryTradeOffOfAFamily) {
  const std::vector<EntrySummary> entries = fill_family();
  // Across tiers the fast path beats every method: one point, which says nothing about the fills.
  const auto cross = family_pareto_fronts(entries, true);
  ASSERT_EQ(cross.size(), 2u);
  EXPECT_EQ(cross[0].second, (std::vector<size_t>{1}));
  // Within the scalar tier: quick, middle, exact, fastest first; the fast path and the other
  // family's dda are no members, the dominated method neither.
  EXPECT_EQ(entries_of(scalar_front(entries, "fill", true)), (std::vector<size_t>{2, 3, 0}));
  EXPECT_EQ(entries_of(scalar_front(entries, "line", false)), (std::vector<size_t>{5, 0}));
  // The overall scalar front: dda, quick, middle, exact.
  EXPECT_EQ(entries_of(scalar_front(entries, "", true)), (std::vector<size_t>{5, 2, 3, 0}));
  EXPECT_EQ(scalar_families(entries), (std::vector<std::string>{"fill", "line"}));
}

TEST(SpeedAccuracyFront, OverlappingNeighboursAreNotSeparated) {
  std::vector<EntrySummary> entries = fill_family();
  for (const FrontPoint& p : scalar_front(entries, "fill", true)) EXPECT_TRUE(p.separated) << p.entry;
  // middle's interval reaches into quick's: both not separated; exact's stays clear of middle's.
  entries[3].seconds_low = 2.05e-3;
  const std::vector<FrontPoint> front = scalar_front(entries, "fill", true);
  ASSERT_EQ(entries_of(front), (std::vector<size_t>{2, 3, 0}));
  EXPECT_FALSE(front[0].separated);
  EXPECT_FALSE(front[1].separated);
  EXPECT_TRUE(front[2].separated);
  // Touching intervals overlap; a single point has no neighbour and is separated.
  EXPECT_FALSE(
      mark_separation({entry("f", "a", 1, 1, 0.5, 2), entry("f", "b", 3, 0, 2, 4)}, {0, 1}, {0, 1}, true)[0].separated);
  EXPECT_TRUE(mark_separation(entries, {0}, {0}, true)[0].separated);
}

// Equally exact ablations of the exact path: the front keeps the one with the lowest median. When
// the other's interval overlaps it, that choice is noise, and the point is not separated.
TEST(SpeedAccuracyFront, AnEquallyAccurateRivalOffTheFrontUnseparatesIt) {
  std::vector<EntrySummary> entries = {entry("exact path", "exact", 4.0, 0.0, 3.9, 4.3),
                                       entry("depth format", "d16", 3.95, 0.0, 3.85, 4.1),
                                       entry("depth format", "d24", 6.0, 0.0, 5.9, 6.1)};
  std::vector<FrontPoint> front = scalar_front(entries, "depth format", true);
  ASSERT_EQ(entries_of(front), (std::vector<size_t>{1}));
  EXPECT_FALSE(front[0].separated);  // exact's interval overlaps d16's
  entries[0].seconds_low = 4.2e-3;   // now exact is measurably slower; d24 was all along
  front = scalar_front(entries, "depth format", true);
  EXPECT_TRUE(front[0].separated);
  // A less accurate entry off the front does not count, however close its time.
  entries.push_back(entry("depth format", "rough", 3.96, 0.5, 3.8, 4.1));
  EXPECT_TRUE(scalar_front(entries, "depth format", true)[0].separated);
}

// Ranked by CPU time, a method that lost the wall-time race to a busy core gets its place back.
TEST(SpeedAccuracyFront, TheClockDecidesTheFront) {
  std::vector<EntrySummary> entries = {entry("exact path", "exact", 4.0, 0.0, 3.9, 4.1),
                                       entry("fill", "quick", 8.0, 0.5, 7.9, 8.1)};  // wall: slowed by another process
  entries[0].cpu_seconds = 4.0e-3;
  entries[0].cpu_seconds_low = 3.9e-3;
  entries[0].cpu_seconds_high = 4.1e-3;
  entries[1].cpu_seconds = 2.0e-3;
  entries[1].cpu_seconds_low = 1.9e-3;
  entries[1].cpu_seconds_high = 2.1e-3;
  entries[1].cpu_runs = {2.0e-3, 1.9e-3};
  EXPECT_EQ(entries_of(scalar_front(entries, "fill", true)), (std::vector<size_t>{0}));
  std::vector<EntrySummary> by_cpu;
  for (const EntrySummary& e : entries) by_cpu.push_back(timed_by(e, FrontClock::Cpu));
  EXPECT_EQ(by_cpu[1].seconds_per_frame, 2.0e-3);
  EXPECT_EQ(by_cpu[1].seconds_high, 2.1e-3);
  EXPECT_EQ(by_cpu[1].wall_runs, entries[1].cpu_runs);
  EXPECT_EQ(entries_of(scalar_front(by_cpu, "fill", true)), (std::vector<size_t>{1, 0}));
  EXPECT_EQ(timed_by(entries[1], FrontClock::Wall).seconds_per_frame, 8.0e-3);
}

TEST(SpeedAccuracyFront, RunSpreadIsTheRangeOverTheMedian) {
  EXPECT_DOUBLE_EQ(run_spread({2.0, 1.0, 4.0}), 1.5);
  EXPECT_DOUBLE_EQ(run_spread({3.0, 3.0}), 0.0);
  EXPECT_DOUBLE_EQ(run_spread({}), 0.0);
}

TEST(SpeedAccuracyFront, CpuModelComesFromCpuinfo) {
  EXPECT_EQ(cpu_model_from_cpuinfo("processor\t: 0\nvendor_id\t: AuthenticAMD\nmodel name\t: AMD EPYC 7B13 64-Core\n"
                                   "processor\t: 1\nmodel name\t: other\n"),
            "AMD EPYC 7B13 64-Core");
  EXPECT_EQ(cpu_model_from_cpuinfo("processor\t: 0\nFeatures\t: fp asimd\n"), "unknown");
}

TEST(SpeedAccuracyFront, JsonRecordsTheRunAndEachFrontPoint) {
  SpeedAccuracyRun run;
  run.repeats = 3;
  run.host = RunHost{"box", "Some CPU", "0123abcd", true, 1.5, 2.25, true};
  run.clock = FrontClock::Wall;  // the synthetic entries carry wall times only
  SceneSetRun set;
  set.name = "triangles";
  set.entries = fill_family();
  set.entries[2].wall_runs = {2.0e-3, 1.0e-3, 4.0e-3};
  set.entries[3].seconds_low = 2.05e-3;
  set.lavapipe = entry("reference", "lavapipe", 3.5, 0, 3, 4, Tier::Reference);
  set.left_out = {{"fill: fill=flood", "needs one sample"}};
  run.sets.push_back(set);
  const nlohmann::json json = nlohmann::json::parse(speed_accuracy_json(run));
  EXPECT_EQ(json["host"], "box");
  EXPECT_EQ(json["cpu_model"], "Some CPU");
  EXPECT_EQ(json["git_commit"], "0123abcd");
  EXPECT_EQ(json["git_dirty"], true);
  EXPECT_EQ(json["load_average_1min_before"], 1.5);
  EXPECT_EQ(json["load_average_1min_after"], 2.25);
  EXPECT_EQ(json["freed_memory_kept"], true);
  EXPECT_EQ(json["repeats"], 3);
  EXPECT_EQ(json["front_clock"], "wall");
  const nlohmann::json& s = json["sets"][0];
  EXPECT_EQ(s["methods"][2]["seconds_spread"], 1.5);
  EXPECT_EQ(s["methods"][2]["seconds_runs"].size(), 3u);
  EXPECT_EQ(s["methods"][1]["tier"], "fast");
  EXPECT_EQ(s["left_out"][0]["entry"], "fill: fill=flood");
  const nlohmann::json& fill = s["family_fronts_coverage"]["fill"];
  ASSERT_EQ(fill.size(), 3u);
  EXPECT_EQ(fill[0]["entry"], "fill: quick");
  EXPECT_EQ(fill[0]["separated"], false);
  EXPECT_EQ(fill[1]["separated"], false);
  EXPECT_EQ(fill[2]["entry"], "exact path: exact");
  EXPECT_EQ(fill[2]["separated"], true);
  EXPECT_FALSE(s["family_fronts_coverage"].contains("fast path"));
  EXPECT_EQ(s["cross_tier_family_fronts_coverage"]["fill"][0], "fast path: threads=2");
}

// Every classic method of `rastercmp methods` is timed, so the chart covers the notes.
TEST(SpeedAccuracyFront, EveryClassicMethodHasAnEntry) {
  std::set<std::string> timed;
  for (const MethodEntry& e : speed_accuracy_entries())
    for (const MethodChoice& c : e.cpu.methods) timed.insert(c.stage + "=" + c.name);
  std::set<std::string> defaults;
  for (const cpu::classic::MethodInfo& m : cpu::classic::method_registry()) {
    const std::string name = std::string(m.stage) + "=" + std::string(m.name);
    if (defaults.insert(std::string(m.stage)).second) continue;  // the first of a stage is its default (README)
    EXPECT_TRUE(timed.count(name)) << name << " has no speed-accuracy entry";
  }
}

// The clipped-line scene makes the clippers work: lines cross the viewport's edges, and every
// vertex is in front of the eye and inside the depth planes, which the 2-D clippers require.
TEST(SpeedAccuracyFront, ClippedLinesCrossTheViewport) {
  const Scene scene = make_clipped_lines(256, 64);
  ASSERT_EQ(scene.draws.size(), 1u);
  const auto& p = scene.draws[0].positions_clip;
  ASSERT_EQ(p.size(), 128u);
  const auto inside = [](const glm::vec4& v) { return std::abs(v.x) <= v.w && std::abs(v.y) <= v.w; };
  size_t one_end_out = 0, both_out = 0;
  for (size_t k = 0; k < p.size(); k += 2) {
    for (const glm::vec4& v : {p[k], p[k + 1]}) {
      EXPECT_GT(v.w, 0.0f);
      EXPECT_GE(v.z, 0.0f);
      EXPECT_LE(v.z, v.w);
    }
    one_end_out += inside(p[k]) != inside(p[k + 1]);
    both_out += !inside(p[k]) && !inside(p[k + 1]);
  }
  EXPECT_GE(one_end_out, 32u);
  EXPECT_GE(both_out, 16u);
}

}  // namespace
}  // namespace rastercmp::experiments
