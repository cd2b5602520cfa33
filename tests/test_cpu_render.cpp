// render_cpu with the lavapipe profile: the result it hands back, the method switches, what the
// profile refuses, and the depth-state rules of the write stage.
#include <string>

#include <gtest/gtest.h>
#include <xmmintrin.h>

#include "cpu_raster/cpu_raster.hpp"
#include "model/errors.hpp"
#include "model/render_result.hpp"

namespace rastercmp {
namespace {

// Two triangles covering a w x h framebuffer at depth z.
Draw full_screen(float z) {
  Draw draw;
  draw.positions_clip = {{-1, -1, z, 1}, {1, -1, z, 1}, {-1, 1, z, 1}, {1, -1, z, 1}, {1, 1, z, 1}, {-1, 1, z, 1}};
  return draw;
}

Scene small_scene(DepthFormat format = DepthFormat::D32Sfloat) {
  Scene scene;
  scene.width = 5;
  scene.height = 3;
  scene.depth_format = format;
  return scene;
}

TEST(CpuRender, ResultNamesTheProfileAndTheArithmetic) {
  Scene scene = small_scene(DepthFormat::D16Unorm);
  scene.draws.push_back(full_screen(0.5f));
  for (const bool fma : {true, false}) {
    CpuOptions options;
    options.fma = fma;
    const RenderResult r = render_cpu(scene, options);
    EXPECT_EQ(r.backend, "cpu");
    EXPECT_EQ(r.device, "cpu lavapipe-22.3.6 profile");
    EXPECT_EQ(r.fma, fma);
    EXPECT_EQ(r.width, 5u);
    EXPECT_EQ(r.height, 3u);
    EXPECT_EQ(r.samples, 1u);
    EXPECT_EQ(r.depth_format, DepthFormat::D16Unorm);
    ASSERT_EQ(r.owner.size(), 15u);
    ASSERT_EQ(r.depth_raw.size(), 15u);
    EXPECT_EQ(r.depth_raw[0], 0x8000u);
  }
}

// docs/lavapipe-rules.md §7.10 (scenes/depth/denormal/clip_z.json): lavapipe reads a denormal
// clip z as 0 (DAZ) even where z/w would be normal, and stores +0; both paths must, whatever the
// caller's own MXCSR, whose mode they leave as they found it (the exception flags are sticky: the
// render's arithmetic may raise them, as any float code may).
TEST(CpuRender, DenormalClipZReadsAsZeroAndTheCallersModeIsRestored) {
  Scene scene = small_scene();
  Draw draw = full_screen(1e-39f);
  for (glm::vec4& p : draw.positions_clip) p *= 1e-5f;  // w = 1e-5: z/w = 1e-34 without DAZ
  for (glm::vec4& p : draw.positions_clip) p.z = 1e-39f;
  scene.draws.push_back(draw);
  const unsigned saved = _mm_getcsr();
  for (const unsigned caller : {saved & ~0x8040u, saved | 0x8040u}) {
    for (const uint32_t threads : {0u, 2u}) {
      _mm_setcsr(caller);
      CpuOptions options;
      options.threads = threads;
      const RenderResult r = render_cpu(scene, options);
      constexpr unsigned kFlags = 0x3Fu;  // IE DE ZE OE UE PE
      EXPECT_EQ(_mm_getcsr() & ~kFlags, caller & ~kFlags) << "threads " << threads;
      _mm_setcsr(saved);
      for (size_t i = 0; i < r.depth_raw.size(); ++i) {
        EXPECT_EQ(owner_draw(r.owner[i]), 0u);
        EXPECT_EQ(r.depth_raw[i], 0u) << "threads " << threads << " sample " << i;
      }
    }
  }
}

TEST(CpuRender, NoDepthAttachmentMeansNoDepthOutput) {
  Scene scene = small_scene(DepthFormat::None);
  scene.draws.push_back(full_screen(0.5f));
  const RenderResult r = render_cpu(scene, CpuOptions{});
  EXPECT_FALSE(r.has_depth());
  for (const uint32_t owner : r.owner) EXPECT_EQ(owner_draw(owner), 0u);
}

TEST(CpuRender, LaterPrimitivesOverwriteAndTheDepthTestDecides) {
  Scene scene = small_scene();
  scene.draws.push_back(full_screen(0.5f));
  scene.draws.push_back(full_screen(0.7f));  // LESS against 0.5: fails everywhere
  Draw closer = full_screen(0.25f);
  scene.draws.push_back(closer);
  const RenderResult r = render_cpu(scene, CpuOptions{});
  for (size_t i = 0; i < r.owner.size(); ++i) {
    EXPECT_EQ(owner_draw(r.owner[i]), 2u);
    EXPECT_EQ(r.depth_raw[i], 0x3E800000u);  // 0.25
  }
}

// docs/lavapipe-rules.md §6: a Bresenham line in a 4x framebuffer is one fragment per pixel, tested
// against sample 0's depth; it writes its depth to sample 0 only and its owner to all four samples.
// 4x4 px: strips at z 0.2 cover samples 0 and 2 of pixel (1, 1) (x < 1.5) and sample 2 alone of
// pixel (2, 1) (2 <= x < 2.25); a horizontal line at z 0.5 crosses row 1; then a full screen at 0.7.
TEST(CpuRender, BresenhamLineIn4xIsOneFragmentTestedAtSampleZero) {
  Scene scene = small_scene();
  scene.width = scene.height = 4;
  scene.samples = 4;
  Draw left, narrow, line;
  left.positions_clip = {{-1, -1, 0.2f, 1}, {-0.25f, -1, 0.2f, 1}, {-0.25f, 1, 0.2f, 1},
                         {-1, -1, 0.2f, 1}, {-0.25f, 1, 0.2f, 1},  {-1, 1, 0.2f, 1}};
  narrow.positions_clip = {{0, -1, 0.2f, 1}, {0.125f, -1, 0.2f, 1}, {0.125f, 1, 0.2f, 1},
                           {0, -1, 0.2f, 1}, {0.125f, 1, 0.2f, 1},  {0, 1, 0.2f, 1}};
  line.topology = Topology::LineList;
  line.state.line_mode = LineMode::Bresenham;
  line.positions_clip = {{-1.5f, -0.2f, 0.5f, 1}, {1.5f, -0.2f, 0.5f, 1}};
  scene.draws = {left, narrow, line, full_screen(0.7f)};
  for (const uint32_t threads : {0u, 2u}) {
    CpuOptions options;
    options.threads = threads;
    const RenderResult r = render_cpu(scene, options);
    // (1, 1): sample 0 holds 0.2, so the line fails there although samples 1 and 3 hold 1.0.
    EXPECT_EQ(owner_draw(r.owner[r.index(1, 1, 0)]), 0u);
    EXPECT_EQ(owner_draw(r.owner[r.index(1, 1, 2)]), 0u);
    EXPECT_EQ(owner_draw(r.owner[r.index(1, 1, 1)]), 3u);
    EXPECT_EQ(owner_draw(r.owner[r.index(1, 1, 3)]), 3u);
    // (2, 1): sample 0 holds 1.0, so the line passes and owns all four samples, sample 2 (0.2)
    // included; its depth 0.5 goes to sample 0 only, so the full screen at 0.7 wins 1 and 3.
    EXPECT_EQ(r.owner[r.index(2, 1, 0)], encode_owner(2, 0));
    EXPECT_EQ(r.owner[r.index(2, 1, 2)], encode_owner(2, 0));
    EXPECT_EQ(owner_draw(r.owner[r.index(2, 1, 1)]), 3u);
    EXPECT_EQ(owner_draw(r.owner[r.index(2, 1, 3)]), 3u);
    EXPECT_EQ(r.depth_raw[r.index(2, 1, 0)], 0x3F000000u);  // 0.5
    EXPECT_EQ(r.depth_raw[r.index(2, 1, 2)], 0x3E4CCCCDu);  // 0.2, kept
    EXPECT_EQ(r.depth_raw[r.index(2, 1, 1)], 0x3F333333u);  // 0.7
  }
}

TEST(CpuRender, DepthTestOffWritesOwnersButNoDepth) {
  Scene scene = small_scene();
  scene.depth_clear = 0.125f;
  Draw draw = full_screen(0.5f);
  draw.state.depth.test_enable = false;  // Vulkan: no test, no write
  scene.draws.push_back(draw);
  const RenderResult r = render_cpu(scene, CpuOptions{});
  for (size_t i = 0; i < r.owner.size(); ++i) {
    EXPECT_EQ(owner_draw(r.owner[i]), 0u);
    EXPECT_EQ(r.depth_raw[i], 0x3E000000u);  // still the clear value 0.125
  }
}

TEST(CpuRender, NeverAndWriteDisabled) {
  Scene scene = small_scene();
  Draw never = full_screen(0.5f);
  never.state.depth.compare_op = CompareOp::Never;
  scene.draws.push_back(never);
  Draw no_write = full_screen(0.25f);
  no_write.state.depth.write_enable = false;
  scene.draws.push_back(no_write);
  const RenderResult r = render_cpu(scene, CpuOptions{});
  for (size_t i = 0; i < r.owner.size(); ++i) {
    EXPECT_EQ(owner_draw(r.owner[i]), 1u);
    EXPECT_EQ(r.depth_raw[i], 0x3F800000u);
  }
}

TEST(CpuRender, UnknownMethodsAreUsageErrors) {
  Scene scene = small_scene();
  scene.draws.push_back(full_screen(0.5f));
  CpuOptions options;
  options.methods = {{"snap", "truncate"}};
  EXPECT_THROW(render_cpu(scene, options), UsageError);
  options.methods = {{"shading", "gouraud"}};
  EXPECT_THROW(render_cpu(scene, options), UsageError);
  options.methods = {{"snap", "round_half_away"}, {"tie_break", "none"}};
  EXPECT_NO_THROW(render_cpu(scene, options));
  options.methods = {{"snap", "round_nearest_even"}, {"tie_break", "top_left"}};
  EXPECT_NO_THROW(render_cpu(scene, options));
}

// The tie-break switch changes exactly the samples on edges: a pixel-aligned square's left and
// top edges pass through no centre, but the diagonal shared by its two triangles does.
TEST(CpuRender, TieBreakNoneDropsSamplesOnTheSharedDiagonal) {
  Scene scene;
  scene.width = scene.height = 4;
  scene.draws.push_back(full_screen(0.5f));
  CpuOptions options;
  const RenderResult exact = render_cpu(scene, options);
  options.methods = {{"tie_break", "none"}};
  const RenderResult none = render_cpu(scene, options);
  int dropped = 0;
  for (size_t i = 0; i < exact.owner.size(); ++i) {
    EXPECT_NE(exact.owner[i], kOwnerBackground);
    dropped += none.owner[i] == kOwnerBackground;
  }
  EXPECT_EQ(dropped, 4);  // the centres with x + y = 3 on the diagonal x + y = 4
}

void expect_not_supported(const Draw& draw, const std::string& mentions) {
  Scene scene = small_scene();
  scene.draws.push_back(draw);
  try {
    render_cpu(scene, CpuOptions{});
    ADD_FAILURE() << "expected NotSupportedError mentioning " << mentions;
  } catch (const NotSupportedError& e) {
    EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
  }
}

TEST(CpuRender, StateTheProfileCannotReproduceIsNotSupported) {
  Draw points = full_screen(0.5f);
  points.topology = Topology::PointList;
  expect_not_supported(points, "point_list");
  Draw wire = full_screen(0.5f);
  wire.state.polygon_mode = PolygonMode::Line;
  expect_not_supported(wire, "polygon_mode");
  Draw smooth = full_screen(0.5f);
  smooth.topology = Topology::LineList;
  smooth.state.line_mode = LineMode::RectangularSmooth;
  expect_not_supported(smooth, "rectangular_smooth");
}

TEST(CpuRender, ScenesOutsideTheModelsPreconditionsAreInputErrors) {
  Scene scene = small_scene();
  scene.samples = 2;
  EXPECT_THROW(render_cpu(scene, CpuOptions{}), InputError);
  Scene bad_index = small_scene();
  Draw draw = full_screen(0.5f);
  draw.indices = {0, 1, 99};
  bad_index.draws.push_back(draw);
  EXPECT_THROW(render_cpu(bad_index, CpuOptions{}), InputError);
}

// The index check names the first index out of range, on the exact and on the fast path.
TEST(CpuRender, FirstIndexOutOfRangeIsNamed) {
  Scene scene = small_scene();
  scene.source_path = "mesh.json";
  Draw draw = full_screen(0.5f);
  draw.indices = {0, 1, 2, 3, 4, 5, 0, 6, 99, 1, 2, 3};  // 6 positions: 6 is the first index out of range
  scene.draws.push_back(draw);
  for (const uint32_t threads : {0u, 2u}) {
    CpuOptions options;
    options.threads = threads;
    try {
      render_cpu(scene, options);
      ADD_FAILURE() << "expected InputError, threads " << threads;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "mesh.json");
      EXPECT_EQ(e.json_path(), "$.draws[0].indices[7]") << "threads " << threads;
    }
  }
}

}  // namespace
}  // namespace rastercmp
