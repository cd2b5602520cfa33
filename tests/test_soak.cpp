// The random differential soak and the reducer (docs/soak.md): the generators are deterministic
// and produce scenes the loader accepts, written scenes load back bit for bit, the reducer
// shrinks a synthetic failure, and on lavapipe a fixed-seed slice passes while a deliberately
// broken model (RASTERCMP_TEST_BREAK_MODEL, test-only) is found and reduced to a few primitives.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>

#include "compare/case_run.hpp"
#include "model/errors.hpp"
#include "model/scene_io.hpp"
#include "soak/judge.hpp"
#include "soak/primitives.hpp"
#include "soak/reduce.hpp"
#include "soak/scene_gen.hpp"
#include "soak/scene_write.hpp"
#include "soak/soak.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::soak {
namespace {

namespace fs = std::filesystem;

#ifdef RASTERCMP_SANITIZER_BUILD
constexpr uint64_t kSlicePrimitives = 1200;  // ASan + UBSan run 3-5x slower
constexpr uint64_t kBrokenPrimitives = 150;
#else
constexpr uint64_t kSlicePrimitives = 6000;
constexpr uint64_t kBrokenPrimitives = 400;
#endif

bool same_bits(const Scene& a, const Scene& b) {
  if (a.draws.size() != b.draws.size()) return false;
  for (size_t d = 0; d < a.draws.size(); ++d) {
    const auto& pa = a.draws[d].positions_clip;
    const auto& pb = b.draws[d].positions_clip;
    if (pa.size() != pb.size() || std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(pa[0])) != 0) return false;
    if (a.draws[d].indices != b.draws[d].indices || a.draws[d].topology != b.draws[d].topology) return false;
  }
  return true;
}

TEST(SoakGenerator, SameSeedSameBytesAndEveryFamilyLoads) {
  for (const std::string& family : family_names()) {
    std::set<std::string> distinct;
    for (uint64_t i = 0; i < 40; ++i) {
      const Scene a = generate_scene(family, 7, i);
      const Scene b = generate_scene(family, 7, i);
      const std::string text = scene_to_json_text(a);
      EXPECT_EQ(text, scene_to_json_text(b)) << family << " " << i;
      // What the soak writes loads back to the same bits and the same text.
      const Scene back = parse_scene(text, "back.json");
      EXPECT_TRUE(same_bits(a, back)) << text;
      EXPECT_EQ(scene_to_json_text(back), text);
      EXPECT_GE(primitive_count(a), 1u);
      distinct.insert(text);
    }
    EXPECT_EQ(distinct.size(), 40u) << family << ": the indices do not vary the scenes";
  }
  EXPECT_NE(scene_to_json_text(generate_scene("tie", 7, 0)), scene_to_json_text(generate_scene("tie", 8, 0)));
  EXPECT_THROW(generate_scene("no_such_family", 1, 0), UsageError);
}

// The classes the soak first found, all modelled now, are generated (and so in the make-test slice).
TEST(SoakGenerator, GeneratesTheClassesItFound) {
  bool huge = false, denormal = false, bresenham_4x = false;
  for (uint64_t i = 0; i < 300; ++i) {
    for (const std::string& family : {std::string("magnitude"), std::string("msaa")}) {
      const Scene s = generate_scene(family, 3, i);
      for (const Draw& d : s.draws) {
        for (const glm::vec4& v : d.positions_clip)
          for (int c = 0; c < 4; ++c) {
            if (v[c] != 0 && std::fabs(v[c]) < 1.1754944e-38f) denormal = true;
            if (v.w == 1 && std::fabs(v[c]) >= 1e11f) huge = true;
          }
        if (s.samples == 4 && d.state.line_mode == LineMode::Bresenham) bresenham_4x = true;
      }
    }
  }
  EXPECT_TRUE(denormal);
  EXPECT_TRUE(bresenham_4x);
  EXPECT_TRUE(huge);
}

TEST(SoakPrimitives, StripAndFanVerticesFollowTheSpecification) {
  Draw strip;
  strip.topology = Topology::TriangleStrip;
  strip.positions_clip.resize(5);
  EXPECT_EQ(primitive_count(strip), 3u);
  EXPECT_EQ(primitive_vertices(strip, 0), (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(primitive_vertices(strip, 1), (std::vector<uint32_t>{1, 3, 2}));
  Draw fan = strip;
  fan.topology = Topology::TriangleFan;
  fan.indices = {4, 3, 2, 1};
  EXPECT_EQ(primitive_count(fan), 2u);
  EXPECT_EQ(primitive_vertices(fan, 1), (std::vector<uint32_t>{2, 1, 4}));
}

// Without a device: a synthetic failure (a culled draw with a vertex right of x = 0.5 and a depth
// bias) among many draws and primitives is reduced to one draw, one primitive, and the state that
// matters; the rest goes.
TEST(SoakReduce, ShrinksASyntheticFailureToWhatMatters) {
  Scene scene = generate_scene("many", 11, 2);
  ASSERT_GT(scene.draws.size(), 5u);
  Draw culprit;
  culprit.topology = Topology::TriangleStrip;
  culprit.positions_clip = {
      {-0.3f, -0.2f, 0.5f, 2}, {0.9f, 0.1f, 0.5f, 2}, {0.1f, 0.7f, 0.5f, 2}, {0.2f, 0.1f, 0.3f, 1}};
  culprit.state.cull_mode = CullMode::Front;
  culprit.state.line_width = 3;
  culprit.state.depth_bias.enable = true;
  scene.draws.insert(scene.draws.begin() + 3, culprit);
  scene.scissor = Rect2D{1, 1, 5, 5};
  auto fails = [](const Scene& s) {
    for (const Draw& d : s.draws)
      if (d.state.cull_mode == CullMode::Front && d.state.depth_bias.enable && is_triangle_topology(d.topology))
        for (const glm::vec4& v : d.positions_clip)
          if (v.x / v.w > 0.4f) return true;
    return false;
  };
  ASSERT_TRUE(fails(scene));
  ReduceStats stats;
  const Scene reduced = reduce_scene(scene, fails, 5000, &stats);
  EXPECT_TRUE(fails(reduced));
  ASSERT_EQ(reduced.draws.size(), 1u);
  EXPECT_EQ(primitive_count(reduced), 1u);
  EXPECT_EQ(reduced.draws[0].topology, Topology::TriangleList);  // unrolled
  EXPECT_EQ(reduced.draws[0].state.line_width, 1.0f);            // state that does not matter is reset
  EXPECT_FALSE(reduced.scissor.has_value());
  for (const glm::vec4& v : reduced.draws[0].positions_clip) EXPECT_EQ(v.w, 1.0f);  // simplified toward w = 1
  EXPECT_FALSE(stats.hit_limit);
  EXPECT_LT(stats.runs, 5000u);
}

class SoakLavapipe : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    try {
      if (list_vulkan_devices().empty()) {
        skip_reason_ = "no Vulkan device";
        return;
      }
      runner_ = std::make_unique<CaseRunner>(CompareProfile::Lavapipe, nullptr, VkOptions{"", true});
    } catch (const EnvironmentError& e) {
      skip_reason_ = e.what();
    }
  }
  static void TearDownTestSuite() { runner_.reset(); }
  void SetUp() override {
    if (!runner_) GTEST_SKIP() << "no Vulkan device: " << skip_reason_;
  }
  void TearDown() override { unsetenv("RASTERCMP_TEST_BREAK_MODEL"); }

  static fs::path out_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("rastercmp_test_soak_" + std::to_string(getpid())) / name;
    fs::remove_all(dir);
    return dir;
  }

  static inline std::unique_ptr<CaseRunner> runner_;
  static inline std::string skip_reason_;
};

// The make-test slice: every family, seed 1, must pass with no failure of any kind.
TEST_F(SoakLavapipe, FixedSeedSliceMatchesLavapipe) {
  SoakOptions o;
  o.seed = 1;
  o.primitives = kSlicePrimitives;
  o.reduce = false;
  const SoakSummary summary = run_soak(*runner_, o);
  EXPECT_GE(summary.primitives, kSlicePrimitives);
  for (const FamilyTally& t : summary.families) EXPECT_GT(t.scenes, 0u) << t.family;
  for (const SoakFailure& f : summary.failures)
    ADD_FAILURE() << f.name << ": " << f.kind << "\n"
                  << scene_to_json_text(
                         generate_scene(f.family, o.seed, std::stoull(f.name.substr(f.name.rfind(".n") + 2))));
  std::printf("%s", format_summary(summary).c_str());
}

// The same slice's start on the fast path at 2 threads with --every-worker's switch: the small
// scenes go through the phases that share a frame between workers (block rows, row balance,
// clipped pieces, unowned rows), which the default soak, one worker a small scene, never reaches.
TEST_F(SoakLavapipe, FastPathEveryWorkerSliceMatchesLavapipe) {
  const auto cpu_options = [](const Scene&) {
    CpuOptions cpu;
    cpu.threads = 2;
    cpu.every_worker = true;
    return cpu;
  };
  CaseRunner fast(CompareProfile::Lavapipe, cpu_options, VkOptions{"", true});
  SoakOptions o;
  o.seed = 2;
  o.primitives = kSlicePrimitives / 2;
  o.reduce = false;
  const SoakSummary summary = run_soak(fast, o);
  EXPECT_GE(summary.primitives, o.primitives);
  for (const SoakFailure& f : summary.failures) ADD_FAILURE() << f.name << ": " << f.kind;
  std::printf("%s", format_summary(summary).c_str());
}

// The broken model is found, and every failure is reduced to a handful of primitives that still
// fail the same way when loaded back from the written file.
TEST_F(SoakLavapipe, BrokenModelIsFoundAndReduced) {
  setenv("RASTERCMP_TEST_BREAK_MODEL", "drop_right", 1);
  SoakOptions o;
  o.seed = 1;
  o.primitives = kBrokenPrimitives;
  o.families = {"tie", "fan", "perspective", "depth"};
  o.out_dir = out_dir("broken").string();
  const SoakSummary summary = run_soak(*runner_, o);
  std::printf("%s", format_summary(summary).c_str());
  ASSERT_GE(summary.failures.size(), 3u);
  for (const SoakFailure& f : summary.failures) {
    EXPECT_EQ(f.kind, "coverage") << f.name;
    ASSERT_TRUE(fs::exists(f.original_path)) << f.name;
    ASSERT_TRUE(fs::exists(f.reduced_path)) << f.name;
    const Scene reduced = load_scene_file(f.reduced_path);
    EXPECT_LE(primitive_count(reduced), 4u) << f.reduced_path;
    EXPECT_LT(primitive_count(reduced), f.primitives) << f.reduced_path;
    EXPECT_EQ(failure_kind(judge(*runner_, reduced)), f.kind) << f.reduced_path;
    const Scene original = load_scene_file(f.original_path);
    EXPECT_EQ(failure_kind(judge(*runner_, original)), f.kind) << f.original_path;
  }
  // With the switch off, the reduced scenes pass: the failure was the broken model's.
  unsetenv("RASTERCMP_TEST_BREAK_MODEL");
  for (const SoakFailure& f : summary.failures)
    EXPECT_EQ(failure_kind(judge(*runner_, load_scene_file(f.reduced_path))), "") << f.reduced_path;
  fs::remove_all(fs::path(o.out_dir).parent_path());
}

TEST_F(SoakLavapipe, BadInputIsAUsageError) {
  SoakOptions o;
  o.primitives = 10;
  o.families = {"no_such_family"};
  EXPECT_THROW(run_soak(*runner_, o), UsageError);
  o.families = {};
  o.primitives = 0;
  EXPECT_THROW(run_soak(*runner_, o), UsageError);
  setenv("RASTERCMP_TEST_BREAK_MODEL", "flip_everything", 1);
  o.primitives = 10;
  EXPECT_THROW(run_soak(*runner_, o), std::invalid_argument);
}

}  // namespace
}  // namespace rastercmp::soak
