// Bresenham line set-up at pixel centres (docs/lavapipe-rules.md §5.4): the diamond-exit tests of lines
// whose start or end lies exactly on a pixel centre, with answers worked out by hand; and 4x rectangular
// lines whose rounded-up box is empty (§5.3), which lavapipe drops.
#include <array>

#include <gtest/gtest.h>

#include "cpu_raster/exact/line_setup.hpp"

namespace rastercmp::cpu {
namespace {

struct LineFixture {
  RasterState state;
  SetupContext context;
  explicit LineFixture(float width) {
    state.line_mode = LineMode::Bresenham;
    state.line_width = width;
    context.framebuffer = PixelRect{0, 0, 95, 95};
    context.region = context.framebuffer;
    context.state = &state;
  }
  LineSetup run(WindowVertex a, WindowVertex b) const { return setup_line({a, b}, 3, context); }
};

// (84.5, 55.5) -> (91, 30), width 6: y-major, going up (dy = 25.5 > 0), start on a centre, so
// draw_start is true and y1diff == 0 counts as already drawn: the start edge stays at y = 55.5,
// snapped 55.0 - on the row-55 samples, a bottom edge, so row 55 is empty (as lavapipe draws it).
// Moving it by +0.5 (the ">" test) would put it at 55.5 and draw row 55.
TEST(CpuBresenhamLine, YMajorUpwardStartOnACentreKeepsItsEdge) {
  const LineSetup setup = LineFixture(6).run(WindowVertex{84.5f, 55.5f, 0}, WindowVertex{91, 30, 0});
  ASSERT_EQ(setup.fate, SetupFate::Rasterized);
  EXPECT_FALSE(setup.x_major);
  EXPECT_TRUE(setup.draw_start);
  // After the swap corners 1 and 2 are the start: y = (55.5 - 0.5) * 256, x = 84 * 256 -/+ 3 * 256.
  EXPECT_EQ(setup.raster.vertex_fixed[1].y.wide(), 55 * 256);
  EXPECT_EQ(setup.raster.vertex_fixed[2].y.wide(), 55 * 256);
  EXPECT_EQ(setup.raster.vertex_fixed[1].x.wide(), 81 * 256);
  EXPECT_EQ(setup.raster.vertex_fixed[2].x.wide(), 87 * 256);
  EXPECT_EQ(setup.bbox.y1, 54);  // ((55 * 256 + 255) >> 8) - 1
}

// (40.5, 10.5) -> (44, 60), width 2: y-major, going down (dy = -49.5 < 0), start on a centre:
// y1diff == 0 counts as not drawn, so the start moves by y_offset = -0.5 and x_offset =
// -0.5 * dx/dy = -0.5 * (-3.5 / -49.5) along the line.
TEST(CpuBresenhamLine, YMajorDownwardStartOnACentreMovesBackHalfAPixel) {
  const LineSetup setup = LineFixture(2).run(WindowVertex{40.5f, 10.5f, 0}, WindowVertex{44, 60, 0});
  ASSERT_EQ(setup.fate, SetupFate::Rasterized);
  EXPECT_FALSE(setup.x_major);
  EXPECT_TRUE(setup.draw_start);
  // x = 40.5 - 0.5 * 0.0707... - 0.5 = 39.9646..., * 256 = 10230.95, snapped 10231.
  EXPECT_EQ(setup.raster.vertex_fixed[0].y.wide(), 2432);  // (10.5 - 0.5 - 0.5) * 256
  EXPECT_EQ(setup.raster.vertex_fixed[3].y.wide(), 2432);
  EXPECT_EQ(setup.raster.vertex_fixed[0].x.wide(), 10231 - 256);
  EXPECT_EQ(setup.raster.vertex_fixed[3].x.wide(), 10231 + 256);
}

// The end tests keep lp_setup_line.c's comparisons: (4.5, 58.5) -> (14.25, 6.5) ends on a row
// (y2diff == 0, draw_end false, "<=" says drawn), so the end edge moves by +0.5 to 7.0, snapped 6.5.
TEST(CpuBresenhamLine, YMajorEndOnARowStillMovesHalfAPixel) {
  const LineSetup setup = LineFixture(6).run(WindowVertex{4.5f, 58.5f, 0}, WindowVertex{14.25f, 6.5f, 0});
  ASSERT_EQ(setup.fate, SetupFate::Rasterized);
  EXPECT_FALSE(setup.draw_end);
  EXPECT_EQ(setup.raster.vertex_fixed[0].y.wide(), int64_t(6.5 * 256));
  EXPECT_EQ(setup.raster.vertex_fixed[1].y.wide(), 58 * 256);  // the start, unmoved
  EXPECT_EQ(setup.bbox.y0, 7);
  EXPECT_EQ(setup.bbox.y1, 57);
}

// (10.5, 20.5) -> (28.5, 26.5), width 2: x-major, going right (dx = -18 < 0: the endpoints are
// swapped), both ends on centres. The end (x2diff == 0, draw_end false) counts as drawn, so it
// moves by x_offset = -0.5 and y_offset = -0.5 * dy/dx = -0.5 * 0.33333334f: x = 28.5 - 0.5 - 0.5
// = 27.5 -> 7040; y = 26.5 - 0.16666667 - 0.5 = 25.833334 -> 6613.33, snapped 6613. Unmoved, the
// side edges would keep slope exactly 1/3 and pass through samples (a one-row difference).
TEST(CpuBresenhamLine, XMajorRightwardEndOnAColumnMovesBackHalfAPixel) {
  const LineSetup setup = LineFixture(2).run(WindowVertex{10.5f, 20.5f, 0}, WindowVertex{28.5f, 26.5f, 0});
  ASSERT_EQ(setup.fate, SetupFate::Rasterized);
  EXPECT_TRUE(setup.x_major);
  EXPECT_TRUE(setup.draw_start);
  EXPECT_FALSE(setup.draw_end);
  // After the swap corners 0 and 3 are the end, corners 1 and 2 the (unmoved) start.
  EXPECT_EQ(setup.raster.vertex_fixed[0].x.wide(), 7040);
  EXPECT_EQ(setup.raster.vertex_fixed[3].x.wide(), 7040);
  EXPECT_EQ(setup.raster.vertex_fixed[0].y.wide(), 6613 - 256);
  EXPECT_EQ(setup.raster.vertex_fixed[3].y.wide(), 6613 + 256);
  EXPECT_EQ(setup.raster.vertex_fixed[1].x.wide(), 10 * 256);
  EXPECT_EQ(setup.raster.vertex_fixed[1].y.wide(), 20 * 256 - 256);
}

// (20.5, 10.5) -> (23.5, 40.5), width 1: y-major, going down (dy = -30 < 0: no swap), the end on
// a row (y2diff == 0, draw_end false) counts as drawn, so it moves by y_offset = -0.5 and
// x_offset = -0.5 * dx/dy = -0.05: y = 40.5 - 0.5 - 0.5 = 39.5 -> 10112; x = 23.5 - 0.05 - 0.5 =
// 22.95 -> 5875.2, snapped 5875, then -/+ half the width (128).
TEST(CpuBresenhamLine, YMajorDownwardEndOnARowMovesBackHalfAPixel) {
  const LineSetup setup = LineFixture(1).run(WindowVertex{20.5f, 10.5f, 0}, WindowVertex{23.5f, 40.5f, 0});
  ASSERT_EQ(setup.fate, SetupFate::Rasterized);
  EXPECT_FALSE(setup.x_major);
  EXPECT_FALSE(setup.draw_end);
  EXPECT_EQ(setup.raster.vertex_fixed[1].y.wide(), 10112);
  EXPECT_EQ(setup.raster.vertex_fixed[2].y.wide(), 10112);
  EXPECT_EQ(setup.raster.vertex_fixed[1].x.wide(), 5875 - 128);
  EXPECT_EQ(setup.raster.vertex_fixed[2].x.wide(), 5875 + 128);
}

// 4x rectangular line (2.5, 2.5) -> (2.5, 3.0), width 1, snap offset 0: the quad is x 512..768,
// y 640..768, so sample 2 of pixel (2, 2) at (544, 672) is inside all four edges; but the box rounded
// up is y 3..2 (((640 + 255) >> 8) = 3, ((768 + 255) >> 8) - 1 = 2), empty, and
// u_rect_test_intersection never lets an empty rectangle intersect, so the line is dropped.
TEST(CpuRectangularLine, MultisampledLineWithAnEmptyBoxIsDropped) {
  LineFixture f(1);
  f.state.line_mode = LineMode::Rectangular;
  f.context.multisample = true;
  const LineSetup setup = f.run(WindowVertex{2.5f, 2.5f, 0}, WindowVertex{2.5f, 3.0f, 0});
  EXPECT_EQ(setup.bbox, (PixelRect{2, 3, 2, 2}));
  EXPECT_TRUE(setup.bbox.empty());
  EXPECT_EQ(setup.fate, SetupFate::OutsideRegion);
  // The same in x: (6.5, 2.5) -> (7.0, 2.5), box x 7..6.
  const LineSetup across = f.run(WindowVertex{6.5f, 2.5f, 0}, WindowVertex{7.0f, 2.5f, 0});
  EXPECT_EQ(across.bbox, (PixelRect{7, 2, 6, 2}));
  EXPECT_EQ(across.fate, SetupFate::OutsideRegion);
  // Half a pixel longer the box is row 3 and the line is rasterized (row 2's samples 2 and 3 too,
  // through its tile).
  const LineSetup longer = f.run(WindowVertex{2.5f, 2.5f, 0}, WindowVertex{2.5f, 3.5f, 0});
  EXPECT_EQ(longer.bbox, (PixelRect{2, 3, 2, 3}));
  EXPECT_EQ(longer.fate, SetupFate::Rasterized);
}

TEST(CpuDrawRegion, EmptyRectanglesNeverTouch) {
  const PixelRect region{0, 0, 15, 15};
  EXPECT_TRUE(rects_touch(region, PixelRect{2, 3, 2, 3}));
  EXPECT_FALSE(rects_touch(region, PixelRect{2, 3, 2, 2}));  // inside the region's bounds, but empty
  EXPECT_FALSE(rects_touch(PixelRect{5, 5, 4, 15}, PixelRect{0, 0, 15, 15}));
}

}  // namespace
}  // namespace rastercmp::cpu
