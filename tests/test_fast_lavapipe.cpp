// The fast CPU path against lavapipe itself (VulkanRenderer, validation layer on): identical
// owner and depth bytes at 1 and 2 threads on seeded random scenes and on small versions of the
// benchmark scenes. Skipped, with the reason, only where no Vulkan device exists.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "bench/bench_scenes.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/scene_io.hpp"
#include "tests/test_fast_support.hpp"
#include "tests/test_vulkan_support.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp {
namespace {

using test::missing_vulkan_reason;

class FastAgainstLavapipe : public ::testing::Test {
 protected:
  static VulkanRenderer& renderer() { return test::shared_renderer(); }

  void SetUp() override {
    const std::string reason = missing_vulkan_reason();
    if (!reason.empty()) GTEST_SKIP() << "no Vulkan device: " << reason;
  }

  // The driver's result (the CPU profile's fma follows the host, as lavapipe does) against the
  // fast path at 1 and 2 threads.
  void expect_same(const Scene& scene, bool with_exact = false) {
    const RenderResult vulkan = renderer().render(scene);
    EXPECT_TRUE(renderer().validation_messages().empty()) << renderer().validation_messages().front();
    if (with_exact) {
      SCOPED_TRACE(scene.name + " exact path");
      EXPECT_TRUE(fast_test::same_bytes(
          vulkan, fast_test::render_exact(scene, renderer().device().fma, test::release_of(renderer()))));
    }
    for (const uint32_t threads : {1u, 2u}) {
      SCOPED_TRACE(scene.name + " threads=" + std::to_string(threads));
      EXPECT_TRUE(
          fast_test::same_bytes(vulkan, fast_test::render_fast(scene, renderer().device().fma, threads,
                                                               fast_test::best_isa(), test::release_of(renderer()))));
    }
  }
};

TEST_F(FastAgainstLavapipe, RandomScenes) {
  fast_test::RandomSceneSpec spec;
  spec.allow_multisample = false;  // 4x scenes against lavapipe: test_differential
  spec.max_primitives = 24;        // one vsplit chunk per draw (docs/lavapipe-rules.md §1.5)
  for (uint64_t seed = 1; seed <= 12; ++seed) expect_same(fast_test::random_scene(1000 + seed, spec));
}

TEST_F(FastAgainstLavapipe, LayeredAndSmallMeshScenes) {
  for (uint64_t seed = 1; seed <= 4; ++seed) expect_same(fast_test::layered_scene(seed));
  expect_same(bench::grid_scene(40, 128));
}

TEST_F(FastAgainstLavapipe, BenchScenesAtSmallSize) {
  expect_same(bench::fill_layers_scene(true, 128, 6));
  expect_same(bench::fill_layers_scene(false, 128, 6));
  expect_same(bench::perspective_scene(16, 128));
}

// One built-in scene per denormal trigger (docs/lavapipe-rules.md §7.10), exact and fast paths
// against the driver: denormal clip z, viewport depth, slope-bias offset, depth-plane gradient
// and clipper t. Each fails without the FTZ/DAZ mode (each differs from lavapipe in coverage or
// depth then). The fast path's pool jobs must set the mode in their own threads (threads=2).
TEST_F(FastAgainstLavapipe, DenormalsFlushLikeLavapipe) {
  const std::string root = std::string(RASTERCMP_SOURCE_DIR) + "/scenes/";
  for (const char* path :
       {"depth/denormal/clip_z.json", "depth/denormal/viewport_depth.json", "depth/denormal/bias_slope.json",
        "depth/denormal/plane_gradient.json", "clip/denormal_t.json", "depth/denormal/clear_clipped.json"})
    expect_same(load_scene_file(root + path), true);
}

// The draw pipeline's primitives are set up outside the denormal mode when the draw ends, inside
// it when a later chunk without clipping is emitted (docs/lavapipe-rules.md §7.11): each of the
// two scenes fails with the other rule. The twelve reduced random scenes of tests/data/scenes/
// denormal-planes (tiny z beside zero, some with a denormal clear value or bias) failed before.
TEST_F(FastAgainstLavapipe, SetupOutsideTheDenormalModeLikeLavapipe) {
  const std::string root = std::string(RASTERCMP_SOURCE_DIR);
  for (const char* path : {"/scenes/depth/denormal/setup_after_draw.json", "/scenes/depth/denormal/setup_before_emit.json"})
    expect_same(load_scene_file(root + path), true);
  for (const auto& entry : std::filesystem::directory_iterator(root + "/tests/data/scenes/denormal-planes"))
    expect_same(load_scene_file(entry.path().string()), true);
}

// A trailing pipelined run longer than one vertex-buffer batch whose set-up differs between the
// modes: where the batches end is not modelled, so both paths refuse the scene, naming the
// primitive; the same draw with one more chunk without clipping after it is modelled (and matches).
TEST_F(FastAgainstLavapipe, UnmodelledSetupBatchesAreRefusedByBothPaths) {
  const Scene scene = fast_test::denormal_setup_batch_scene(60, false);
  const bool fma = renderer().device().fma;
  const LavapipeRelease& release = test::release_of(renderer());
  for (const uint32_t threads : {0u, 1u, 2u}) {
    SCOPED_TRACE("threads=" + std::to_string(threads));
    try {
      threads == 0 ? fast_test::render_exact(scene, fma, release)
                   : fast_test::render_fast(scene, fma, threads, fast_test::best_isa(), release);
      ADD_FAILURE() << "accepted";
    } catch (const NotSupportedError& e) {
      EXPECT_NE(std::string(e.what()).find("draw 0 primitive 0: its set-up gives a different result"),
                std::string::npos)
          << e.what();
    }
  }
  expect_same(fast_test::denormal_setup_batch_scene(60, true), true);
}

// The huge w = 1 triangle whose clipped pieces overflow llvmpipe's int32 set-up (rules §7.5): both
// sides of the boundary (every sample, nothing), 1x and 4x, exact and fast (which hands such a
// triangle to the exact rasterizer, in submission order, on each worker's rows). Each covers-all
// scene fails without the binned model (the plane test covers half the columns).
// Mesa 26.2 reworked that arithmetic, which the profile refuses rather than model
// (docs/lavapipe-rules.md §8.7): both paths then say NotSupported for the two scenes that draw
// through it, and the third, whose vertex snaps past int32 and draws nothing, still matches.
TEST_F(FastAgainstLavapipe, WrappingSetupLikeLavapipe) {
  const std::string root = std::string(RASTERCMP_SOURCE_DIR) + "/scenes/triangle/huge/";
  const LavapipeRelease& release = test::release_of(renderer());
  const bool refuses = release.rules().has(LavapipeRule::RasterizerOverflowReworked);
  for (const char* path : {"wraps_covers_all.json", "wraps_covers_all_4x.json"}) {
    const Scene scene = load_scene_file(root + path);
    if (!refuses) {
      expect_same(scene, true);
      continue;
    }
    SCOPED_TRACE(std::string(path) + ", " + release.profile);
    const bool fma = renderer().device().fma;
    EXPECT_THROW(fast_test::render_exact(scene, fma, release), NotSupportedError);
    EXPECT_THROW(fast_test::render_fast(scene, fma, 2, fast_test::best_isa(), release), NotSupportedError);
  }
  expect_same(load_scene_file(root + "wraps_covers_none.json"), true);
}

}  // namespace
}  // namespace rastercmp
