// Each classic method, selected on a real scene, pinned with numbers against the exact path
// (docs/methods.md "Selecting a method"; scenes in scenes/methods/).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cpu_raster/classic/classic_clip.hpp"
#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/viewport.hpp"
#include "model/errors.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace {

Scene method_scene(const std::string& relative) {
  return load_scene_file(std::string(RASTERCMP_SOURCE_DIR) + "/scenes/methods/" + relative + ".json");
}

RenderResult render_with(const Scene& scene, std::vector<MethodChoice> methods) {
  CpuOptions options;
  options.fma = true;
  options.methods = std::move(methods);
  return options.methods.empty() ? render_cpu(scene, options) : render_classic(scene, options);
}

size_t owner_differences(const RenderResult& a, const RenderResult& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.owner.size(); ++i) n += a.owner[i] != b.owner[i];
  return n;
}

size_t depth_differences(const RenderResult& a, const RenderResult& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.depth_raw.size(); ++i) n += a.depth_raw[i] != b.depth_raw[i];
  return n;
}

// Pixels covered by both triangles of the quad, each rendered alone.
size_t double_covered(const Scene& quad, const std::vector<MethodChoice>& methods) {
  std::vector<RenderResult> alone;
  for (size_t t = 0; t < 2; ++t) {
    Scene one = quad;
    one.draws[0].positions_clip.assign(quad.draws[0].positions_clip.begin() + 3 * t,
                                       quad.draws[0].positions_clip.begin() + 3 * t + 3);
    alone.push_back(render_with(one, methods));
  }
  size_t both = 0;
  for (size_t i = 0; i < alone[0].owner.size(); ++i)
    both += alone[0].owner[i] != kOwnerBackground && alone[1].owner[i] != kOwnerBackground;
  return both;
}

TEST(ClassicFill, FloatEdgeDoubleCoversExactlyTheSharedDiagonal) {
  const Scene quad = method_scene("fill/float_edge/shared_edge_quad");
  EXPECT_EQ(double_covered(quad, {{"fill", "float_edge"}}), 16u);  // centres (k+.5, k+.5), k = 4..19
  EXPECT_EQ(double_covered(quad, {{"fill", "exact"}}), 0u);
  EXPECT_EQ(double_covered(quad, {{"fill", "scanline"}}), 0u);
  EXPECT_EQ(owner_differences(render_with(quad, {{"fill", "float_edge"}}), render_with(quad, {})), 16u);
}

TEST(ClassicVisibility, PainterFailsOnCyclicSticksWhereBspMatchesTheZBuffer) {
  const Scene sticks = method_scene("visibility/painter/cyclic_sticks");
  const RenderResult zbuffer = render_with(sticks, {});
  EXPECT_GT(owner_differences(render_with(sticks, {{"visibility", "painter"}}), zbuffer), 0u);
  EXPECT_EQ(owner_differences(render_with(sticks, {{"visibility", "bsp"}}), zbuffer), 0u);
  EXPECT_EQ(depth_differences(render_with(sticks, {{"visibility", "bsp"}}), zbuffer), 0u);
}

TEST(ClassicDepth, NoFmaMovesDepthBitsButNotCoverageOnASteepPlane) {
  const Scene steep = method_scene("depth/no_fma/steep_plane");
  const RenderResult exact = render_with(steep, {});
  const RenderResult unfused = render_with(steep, {{"depth", "no_fma"}});
  EXPECT_EQ(owner_differences(unfused, exact), 0u);
  EXPECT_GT(depth_differences(unfused, exact), 0u);
}

TEST(ClassicLine, DdaAndBresenhamAddTheEndPixelsVulkanLeavesOut) {
  const Scene lines = method_scene("line/dda/inside_endpoints");
  const RenderResult exact = render_with(lines, {});
  EXPECT_GT(owner_differences(render_with(lines, {{"line", "dda"}}), exact), 0u);
  EXPECT_GT(owner_differences(render_with(lines, {{"line", "bresenham"}}), exact), 0u);
}

TEST(ClassicClip, CohenSutherlandNeedsSeveralPassesWhereLiangBarskyNeedsOne) {
  const Scene scene = method_scene("clip/liang_barsky/clipped_lines");
  const cpu::ViewportTransform viewport = cpu::make_viewport_transform(scene.effective_viewport());
  const auto& p = scene.draws[0].positions_clip;
  const auto clip = [&](size_t first, cpu::classic::LineClipper clipper) {
    const std::array<cpu::ClipVertex, 2> line{cpu::make_clip_vertex(p[first], viewport, true, true),
                                              cpu::make_clip_vertex(p[first + 1], viewport, true, true)};
    return cpu::classic::clip_line_classic(line, viewport, true, clipper);
  };
  // Line 1 crosses the framebuffer, entering and leaving through sides it crossed outside first.
  const auto cs = clip(2, cpu::classic::LineClipper::CohenSutherland3d);
  const auto lb = clip(2, cpu::classic::LineClipper::LiangBarsky);
  ASSERT_TRUE(cs.visible && lb.visible);
  EXPECT_GE(cs.passes, 3);
  EXPECT_EQ(lb.passes, 1);
  EXPECT_GT(cs.clips, 2);  // more cuts than the two endpoints that move
  EXPECT_EQ(lb.clips, 2);
  // Line 0 passes the corner outside: Cohen–Sutherland cuts before it can reject.
  const auto cs_miss = clip(0, cpu::classic::LineClipper::CohenSutherland3d);
  const auto lb_miss = clip(0, cpu::classic::LineClipper::LiangBarsky);
  EXPECT_FALSE(cs_miss.visible || lb_miss.visible);
  EXPECT_GE(cs_miss.passes, 2);
  EXPECT_EQ(lb_miss.passes, 1);
}

TEST(ClassicCull, NormalDotViewIgnoresTheViewportFlip) {
  const Scene normal = method_scene("cull/normal_dot_view/back");
  const Scene flipped = method_scene("cull/normal_dot_view/flipped_viewport");
  EXPECT_EQ(owner_differences(render_with(normal, {{"cull", "normal_dot_view"}}), render_with(normal, {})), 0u);
  EXPECT_GT(owner_differences(render_with(flipped, {{"cull", "normal_dot_view"}}), render_with(flipped, {})), 0u);
}

TEST(ClassicMethods, AllExactIsTheExactPathBitForBit) {
  for (const char* relative : {"fill/scanline/fan", "visibility/bsp/cyclic_sticks", "line/dda/inside_endpoints",
                               "clip/sutherland_hodgman/clipped_triangles", "depth/no_fma/steep_plane"}) {
    const Scene scene = method_scene(relative);
    const std::vector<MethodChoice> all_exact{{"clip", "exact"},  {"fill", "exact"},         {"line", "exact"},
                                              {"depth", "exact"}, {"visibility", "zbuffer"}, {"cull", "exact"}};
    const RenderResult exact = render_with(scene, {});
    const RenderResult classic = render_with(scene, all_exact);
    EXPECT_EQ(classic.owner, exact.owner) << relative;
    EXPECT_EQ(classic.depth_raw, exact.depth_raw) << relative;
  }
}

TEST(ClassicMethods, UnknownStageOrNameIsAUsageErrorListingTheValidOnes) {
  const Scene scene = method_scene("fill/scanline/fan");
  try {
    render_with(scene, {{"fill", "flood"}});
    FAIL() << "fill=flood was accepted";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("scanline, float_edge, even_odd, winding"), std::string::npos);
  }
  try {
    render_with(scene, {{"shading", "gouraud"}});
    FAIL() << "shading=gouraud was accepted";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("clip, fill, line, depth, visibility, cull"), std::string::npos);
  }
  CpuOptions options;
  options.methods = {{"snap", "round_half_away"}};
  EXPECT_FALSE(uses_classic_methods(options));
  options.methods.push_back({"fill", "scanline"});
  EXPECT_TRUE(uses_classic_methods(options));
}

}  // namespace
}  // namespace rastercmp
