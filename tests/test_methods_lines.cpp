// Line scan conversion: DDA and Bresenham in all octants.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

#include "cpu_raster/methods/line_bresenham.hpp"
#include "cpu_raster/methods/line_dda.hpp"

namespace m = rastercmp::methods;
using m::PixelXY;

namespace {

using Line = std::vector<PixelXY>;

std::set<PixelXY> as_set(const Line& line) { return {line.begin(), line.end()}; }

rc::Gen<PixelXY> endpoint() {
  return rc::gen::construct<PixelXY>(rc::gen::resize(100, rc::gen::inRange(-40, 41)),
                                     rc::gen::resize(100, rc::gen::inRange(-40, 41)));
}

// Distance along the minor axis from the ideal line through p0, p1 to pixel p.
double minor_axis_error(PixelXY p0, PixelXY p1, PixelXY p) {
  const double dx = p1.x - p0.x, dy = p1.y - p0.y;
  if (std::fabs(dy) > std::fabs(dx)) return std::fabs(p0.x + dx * (p.y - p0.y) / dy - p.x);
  return std::fabs(p0.y + dy * (p.x - p0.x) / dx - p.y);
}

// Same pixel count as steps + 1, both endpoints, consecutive pixels 8-adjacent, one per major step.
void check_line_shape(PixelXY p0, PixelXY p1, const Line& line) {
  const int steps = std::max(std::abs(p1.x - p0.x), std::abs(p1.y - p0.y));
  RC_ASSERT(line.size() == size_t(steps) + 1);
  RC_ASSERT(as_set(line).count(p0) == 1u);
  RC_ASSERT(as_set(line).count(p1) == 1u);
  RC_ASSERT(as_set(line).size() == line.size());
  for (size_t i = 1; i < line.size(); ++i) {
    RC_ASSERT(std::max(std::abs(line[i].x - line[i - 1].x), std::abs(line[i].y - line[i - 1].y)) == 1);
  }
  for (const PixelXY& p : line) {
    if (steps > 0) RC_ASSERT(minor_axis_error(p0, p1, p) <= 0.5 + 1e-9);
  }
}

}  // namespace

// Slope 3/8: ideal y = 0, .375, .75, 1.125, 1.5, 1.875, 2.25, 2.625, 3; the half at x = 4 goes up.
TEST(MethodsLines, BresenhamNotesConvention) {
  const Line expected{{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}, {6, 2}, {7, 3}, {8, 3}};
  EXPECT_EQ(m::line_bresenham({0, 0}, {8, 3}), expected);
  EXPECT_EQ(m::line_dda({0, 0}, {8, 3}), expected);
  // Drawn backwards, Bresenham swaps the ends ("if x0 > x1 then swap") and plots from (0,0) up.
  EXPECT_EQ(m::line_bresenham({8, 3}, {0, 0}), expected);
  // DDA keeps p0 -> p1 order.
  EXPECT_EQ(m::line_dda({8, 3}, {0, 0}).front(), (PixelXY{8, 3}));
}

TEST(MethodsLines, SteepLinesSwapRoles) {
  const Line steep = m::line_bresenham({0, 0}, {2, 5});  // ideal x = 0, .4, .8, 1.2, 1.6, 2
  EXPECT_EQ(steep, (Line{{0, 0}, {0, 1}, {1, 2}, {1, 3}, {2, 4}, {2, 5}}));
  EXPECT_EQ(m::line_dda({0, 0}, {2, 5}), steep);
  EXPECT_EQ(m::line_dda({3, 3}, {3, 3}), (Line{{3, 3}}));
  EXPECT_EQ(m::line_bresenham({3, 3}, {3, 3}), (Line{{3, 3}}));
}

// Pinned difference: (0,0) -> (2,-1) has its ideal y = -0.5 at x = 1. DDA's round(y) =
// floor(y + 0.5) takes 0; Bresenham's "2 * error >= deltax" steps towards y1 and takes -1.
TEST(MethodsLines, DdaAndBresenhamDifferOnANegativeHalf) {
  EXPECT_EQ(m::line_dda({0, 0}, {2, -1}), (Line{{0, 0}, {1, 0}, {2, -1}}));
  EXPECT_EQ(m::line_bresenham({0, 0}, {2, -1}), (Line{{0, 0}, {1, -1}, {2, -1}}));
}

// Every octant: the right number of pixels, both endpoints, 8-connected, within half a pixel of
// the ideal line along the minor axis.
RC_GTEST_PROP(MethodsLinesProperty, BothAlgorithmsDrawValidLines, ()) {
  const PixelXY p0 = *endpoint(), p1 = *endpoint();
  check_line_shape(p0, p1, m::line_dda(p0, p1));
  check_line_shape(p0, p1, m::line_bresenham(p0, p1));
}

// On the exact octant lines (horizontal, vertical, diagonal) there is nothing to round: the two
// algorithms draw the same pixels.
RC_GTEST_PROP(MethodsLinesProperty, SamePixelsOnExactOctantLines, ()) {
  const PixelXY p0 = *endpoint();
  const int length = *rc::gen::resize(100, rc::gen::inRange(0, 40));
  const int direction = *rc::gen::resize(100, rc::gen::inRange(0, 8));
  const int dx[8] = {1, 1, 0, -1, -1, -1, 0, 1}, dy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
  const PixelXY p1{p0.x + dx[direction] * length, p0.y + dy[direction] * length};
  RC_ASSERT(as_set(m::line_dda(p0, p1)) == as_set(m::line_bresenham(p0, p1)));
}

// Elsewhere they may differ, but only on exact halves: where they disagree the ideal line is
// half-way between the two choices.
RC_GTEST_PROP(MethodsLinesProperty, DifferencesAreHalfwayTies, ()) {
  const PixelXY p0 = *endpoint(), p1 = *endpoint();
  const std::set<PixelXY> dda = as_set(m::line_dda(p0, p1)), bresenham = as_set(m::line_bresenham(p0, p1));
  for (const PixelXY& p : dda) {
    if (!bresenham.count(p)) RC_ASSERT(std::fabs(minor_axis_error(p0, p1, p) - 0.5) < 1e-9);
  }
}
