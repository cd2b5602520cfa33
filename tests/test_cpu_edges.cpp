// Edge functions and the top-left rule (docs/lavapipe-rules.md §2.4), and coverage of small triangles and
// lines whose covered pixels are worked out by hand.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/edge_plane.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu {
namespace {

FixedPoint at(int32_t x, int32_t y) { return FixedPoint{Fixed24_8{x}, Fixed24_8{y}}; }

// Edges of a counter-clockwise (positive area, y down) polygon; a sample on the edge is at E == 0
// before the bias, so it is covered iff the edge got the +1.
TEST(CpuEdges, LeftEdgeTraversedDownwardIsInclusive) {
  const EdgePlane e = make_edge(at(0, 0), at(0, 256), TieBreak::TopLeft);
  EXPECT_EQ(e.dcdx, -256);
  EXPECT_TRUE(e.inclusive);
  EXPECT_EQ(edge_value(e, 0, 128), 1);  // on the edge: covered
}

TEST(CpuEdges, RightEdgeTraversedUpwardIsExclusive) {
  const EdgePlane e = make_edge(at(0, 256), at(0, 0), TieBreak::TopLeft);
  EXPECT_EQ(e.dcdx, 256);
  EXPECT_FALSE(e.inclusive);
  EXPECT_EQ(edge_value(e, 0, 128), 0);     // on the edge: not covered
  EXPECT_EQ(edge_value(e, -1, 128), 256);  // just inside (left of it)
}

TEST(CpuEdges, TopEdgeTraversedRightToLeftIsInclusive) {
  const EdgePlane e = make_edge(at(256, 0), at(0, 0), TieBreak::TopLeft);
  EXPECT_EQ(e.dcdx, 0);
  EXPECT_EQ(e.dcdy, 256);
  EXPECT_TRUE(e.inclusive);
  EXPECT_EQ(edge_value(e, 128, 0), 1);
}

TEST(CpuEdges, BottomEdgeTraversedLeftToRightIsExclusive) {
  const EdgePlane e = make_edge(at(0, 256), at(256, 256), TieBreak::TopLeft);
  EXPECT_EQ(e.dcdy, -256);
  EXPECT_FALSE(e.inclusive);
  EXPECT_EQ(edge_value(e, 128, 256), 0);
}

TEST(CpuEdges, SlopedEdgesFollowTheSignOfDcdx) {
  EXPECT_TRUE(make_edge(at(0, 0), at(-100, 300), TieBreak::TopLeft).inclusive);  // going down: left
  EXPECT_FALSE(make_edge(at(0, 300), at(100, 0), TieBreak::TopLeft).inclusive);  // going up: right
}

TEST(CpuEdges, TieBreakNoneLeavesEveryEdgeExclusive) {
  const EdgePlane left = make_edge(at(0, 0), at(0, 256), TieBreak::None);
  const EdgePlane top = make_edge(at(256, 0), at(0, 0), TieBreak::None);
  EXPECT_FALSE(left.inclusive);
  EXPECT_FALSE(top.inclusive);
  EXPECT_EQ(edge_value(left, 0, 128), 0);  // the sample on the edge is now out
  EXPECT_EQ(edge_value(top, 128, 0), 0);
}

// A 8x8 single-sample scene drawn with one primitive; '#' marks the covered pixels.
std::vector<std::string> covered_rows(const Scene& scene) {
  const RenderResult result = render_cpu(scene, CpuOptions{});
  std::vector<std::string> rows(scene.height, std::string(scene.width, '.'));
  for (uint32_t y = 0; y < scene.height; ++y)
    for (uint32_t x = 0; x < scene.width; ++x)
      if (result.owner[result.index(x, y)] != kOwnerBackground) rows[y][x] = '#';
  return rows;
}

// Window position (power-of-two framebuffer: exact) → clip position.
glm::vec4 clip(float x, float y) { return {x / 4 - 1, y / 4 - 1, 0.5f, 1}; }

Scene scene_with(Topology topology, std::vector<glm::vec4> positions, LineMode mode = LineMode::Default) {
  Scene scene;
  scene.width = scene.height = 8;
  Draw draw;
  draw.topology = topology;
  draw.positions_clip = std::move(positions);
  draw.state.line_mode = mode;
  scene.draws.push_back(draw);
  return scene;
}

// Vertices on the centres (2.5,0.5), (6.5,4.5), (2.5,6.5): the left edge x = 2.5 is inclusive,
// the slanted upper-right edge and the lower edge are exclusive, so (2,0), (2,6) and the centres
// on the slanted edges, e.g. (3,1) and (6,4), are out.
TEST(CpuEdges, TriangleOnPixelCentresFollowsTheTopLeftRule) {
  const Scene scene = scene_with(Topology::TriangleList, {clip(2.5f, 0.5f), clip(6.5f, 4.5f), clip(2.5f, 6.5f)});
  const std::vector<std::string> expected = {"........", "..#.....", "..##....", "..###...",
                                             "..####..", "..##....", "........", "........"};
  EXPECT_EQ(covered_rows(scene), expected);
}

// Rectangular line (1, 2.5) -> (5, 2.5), width 1: quad x in [0.5, 4.5) px, y in [1.5, 2.5] px of
// the centre frame, i.e. centres x = 1..4 of row 2 (x = 4.5 is on the exclusive right edge).
TEST(CpuEdges, RectangularLineCoversItsRectangle) {
  const Scene scene = scene_with(Topology::LineList, {clip(1, 2.5f), clip(5, 2.5f)});
  const std::vector<std::string> expected = {"........", "........", ".####...", "........",
                                             "........", "........", "........", "........"};
  EXPECT_EQ(covered_rows(scene), expected);
}

// Bresenham line from the centre of (0,0) to the centre of (4,0): the start diamond is drawn, the
// end one is not (diamond exit), so pixels 0..3 of row 0.
TEST(CpuEdges, BresenhamLineIsHalfOpenAtItsEnd) {
  const Scene scene = scene_with(Topology::LineList, {clip(0.5f, 0.5f), clip(4.5f, 0.5f)}, LineMode::Bresenham);
  const std::vector<std::string> expected = {"####....", "........", "........", "........",
                                             "........", "........", "........", "........"};
  EXPECT_EQ(covered_rows(scene), expected);
}

}  // namespace
}  // namespace rastercmp::cpu
