// Bresenham line set-up at pixel centres (lavapipe-rules §5.4): the diamond-exit start tests of
// y-major lines whose start lies exactly on a pixel centre, with answers worked out by hand.
#include <array>

#include <gtest/gtest.h>

#include "cpu_raster/line_setup.hpp"

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

}  // namespace
}  // namespace rastercmp::cpu
