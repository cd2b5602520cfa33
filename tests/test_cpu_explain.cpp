// explain_pixel replays the exact path for one sample: its records must end where the render ends
// (owner and stored depth), and name why each primitive did or did not get there.
#include <string>

#include <gtest/gtest.h>

#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/explain.hpp"
#include "model/errors.hpp"
#include "model/render_result.hpp"
#include "tests/test_differential_scenes.hpp"

namespace rastercmp {
namespace {

// The owner and depth a sample ends with according to its records.
struct Ending {
  uint32_t owner = kOwnerBackground;
  std::optional<uint32_t> depth;
};

Ending ending_of(const std::vector<FragmentRecord>& records) {
  Ending e;
  for (const FragmentRecord& r : records) {
    if (r.owner_written) e.owner = encode_owner(r.draw_index, r.primitive_index);
    if (r.depth_tested) e.depth = r.stored_after;
  }
  return e;
}

void expect_explain_matches_render(const Scene& scene, uint32_t step) {
  const CpuOptions options;
  const RenderResult render = render_cpu(scene, options);
  int checked_covered = 0;
  for (uint32_t y = 0; y < scene.height; y += step)
    for (uint32_t x = 0; x < scene.width; x += step)
      for (uint32_t s = 0; s < scene.samples; ++s) {
        const Ending e = ending_of(explain_pixel(scene, options, x, y, s));
        const size_t i = render.index(x, y, s);
        ASSERT_EQ(e.owner, render.owner[i]) << scene.name << " (" << x << ", " << y << ") sample " << s;
        if (e.depth) {
          EXPECT_EQ(*e.depth, render.depth_raw[i]) << scene.name << " (" << x << ", " << y << ")";
        }
        checked_covered += e.owner != kOwnerBackground;
      }
  EXPECT_GT(checked_covered, 0) << scene.name;
}

TEST(CpuExplain, RecordsEndWhereTheRenderEnds) {
  expect_explain_matches_render(differential::grid_triangles(7), 5);
  expect_explain_matches_render(differential::bias_cull_triangles(3), 4);
  expect_explain_matches_render(differential::clamp_scissor_triangles(2), 4);
  expect_explain_matches_render(differential::line_scene(4, LineMode::Bresenham), 4);
  expect_explain_matches_render(differential::msaa_less_triangles(1), 6);
}

Scene two_triangles() {
  Scene scene;
  scene.width = scene.height = 8;
  scene.depth_format = DepthFormat::D16Unorm;
  Draw back;  // counter-clockwise on screen: front-facing
  back.positions_clip = {{-1, -1, 0.75f, 1}, {-1, 1, 0.75f, 1}, {1, -1, 0.75f, 1}};
  scene.draws.push_back(back);
  Draw front = back;  // the same triangle, nearer, then a clockwise copy culled as back-facing
  for (glm::vec4& p : front.positions_clip) p.z = 0.25f;
  front.state.cull_mode = CullMode::Back;
  front.positions_clip.push_back({-1, -1, 0.1f, 1});
  front.positions_clip.push_back({1, -1, 0.1f, 1});
  front.positions_clip.push_back({-1, 1, 0.1f, 1});
  scene.draws.push_back(front);
  return scene;
}

TEST(CpuExplain, NamesCullingCoverageAndTheDepthTest) {
  const std::vector<FragmentRecord> records = explain_pixel(two_triangles(), CpuOptions{}, 1, 1);
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[0].cull, CullReason::None);
  EXPECT_TRUE(records[0].covered);
  EXPECT_EQ(records[0].stored_before, 0xFFFFu);  // the clear value
  EXPECT_EQ(records[0].depth_raw, 0xBFFFu);      // 0.75
  EXPECT_TRUE(records[0].depth_passed);
  EXPECT_EQ(records[1].stored_before, 0xBFFFu);
  EXPECT_EQ(records[1].depth_raw, 0x4000u);  // 0.25
  EXPECT_TRUE(records[1].owner_written);
  EXPECT_EQ(records[1].edge_count, 3u);
  EXPECT_EQ(records[2].cull, CullReason::Facing);
  EXPECT_FALSE(records[2].front_facing);
  EXPECT_FALSE(records[2].owner_written);
  const std::string text = format_explanation(records);
  EXPECT_NE(text.find("culled: facing"), std::string::npos) << text;
  EXPECT_NE(text.find("written"), std::string::npos) << text;
  EXPECT_NE(text.find("0x4000"), std::string::npos) << text;
}

// Pixel (6,6) lies in the triangle's box but beyond its hypotenuse (the edge from (-1,1) to
// (1,-1) in clip space, i.e. edge 1 of the swapped order).
TEST(CpuExplain, NamesTheEdgeThatExcludesTheSample) {
  const std::vector<FragmentRecord> records = explain_pixel(two_triangles(), CpuOptions{}, 6, 6);
  ASSERT_GE(records.size(), 1u);
  EXPECT_FALSE(records[0].covered);
  EXPECT_EQ(records[0].miss, MissReason::Edge);
  EXPECT_LE(records[0].edge_value[size_t(records[0].failing_plane)], 0);
}

TEST(CpuExplain, NamesTheScissor) {
  Scene scene = two_triangles();
  scene.scissor = Rect2D{3, 3, 2, 2};
  const std::vector<FragmentRecord> records = explain_pixel(scene, CpuOptions{}, 1, 1);
  ASSERT_GE(records.size(), 1u);
  EXPECT_EQ(records[0].miss, MissReason::Scissor);
  EXPECT_EQ(records[0].scissor_plane_count, 4u);
}

TEST(CpuExplain, RejectsSamplesOutsideTheFramebuffer) {
  EXPECT_THROW(explain_pixel(two_triangles(), CpuOptions{}, 8, 0), UsageError);
  EXPECT_THROW(explain_pixel(two_triangles(), CpuOptions{}, 0, 0, 1), UsageError);
  EXPECT_EQ(format_explanation({}), "no primitive reached this pixel\n");
}

}  // namespace
}  // namespace rastercmp
