// Line clipping methods (cpu_raster/methods/clip_line_*.hpp): the lecture notes' worked examples
// as unit tests, and agreement between the clippers as properties.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <stdexcept>

#include "cpu_raster/methods/clip_line_cohen_sutherland.hpp"
#include "cpu_raster/methods/clip_line_cohen_sutherland_3d.hpp"
#include "cpu_raster/methods/clip_line_cyrus_beck.hpp"
#include "cpu_raster/methods/clip_line_liang_barsky.hpp"

namespace m = rastercmp::methods;
using m::Rect2;
using m::Segment2;
using m::Vec2;

namespace {

constexpr double kTol = 1e-9;

void expect_point(Vec2 actual, Vec2 expected, double tol = 1e-12) {
  EXPECT_NEAR(actual.x, expected.x, tol);
  EXPECT_NEAR(actual.y, expected.y, tol);
}

// A value on a 2^-16 grid in [lo, hi): varied, yet exactly on windows' sides now and then.
// Uniform over the whole range at every test size (rapidcheck scales inRange by size otherwise).
rc::Gen<double> coordinate(double lo, double hi) {
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange<int64_t>(0, int64_t(1) << 16)),
                      [=](int64_t k) { return lo + (hi - lo) * double(k) / double(int64_t(1) << 16); });
}

Rect2 random_window() {
  const double x0 = *coordinate(-5, 5), y0 = *coordinate(-5, 5);
  const double w = *coordinate(0.25, 8), h = *coordinate(0.25, 8);
  return {x0, y0, x0 + w, y0 + h};
}

Segment2 random_segment() {
  return {{*coordinate(-12, 12), *coordinate(-12, 12)}, {*coordinate(-12, 12), *coordinate(-12, 12)}};
}

double length(Segment2 s) { return std::hypot(s.p1.x - s.p0.x, s.p1.y - s.p0.y); }

bool inside(Vec2 p, const Rect2& w, double tol) {
  return p.x >= w.x_min - tol && p.x <= w.x_max + tol && p.y >= w.y_min - tol && p.y <= w.y_max + tol;
}

// Distance of p from the line through s (s must have length).
double distance_to_line(Vec2 p, Segment2 s) { return std::fabs(m::cross(s.p1 - s.p0, p - s.p0)) / length(s); }

}  // namespace

// notes-line-clipping-hidden-surface.txt, "Example": (2,3)-(8,6) against 3<=x<=7, 2<=y<=4
// gives (3, 3.5)-(4.0, 4.0).
TEST(MethodsLineClip, NotesExampleCohenSutherland) {
  const Rect2 window{3, 2, 7, 4};
  const m::CohenSutherlandResult r = m::clip_line_cohen_sutherland({{2, 3}, {8, 6}}, window);
  ASSERT_TRUE(r.accepted);
  expect_point(r.segment.p0, {3, 3.5});
  expect_point(r.segment.p1, {4, 4});
  // (2,3) is left only: one clip; (8,6) is top and right: top first lands on (4,4), inside.
  EXPECT_EQ(r.clips, 2);
  EXPECT_EQ(r.passes, 3);
}

TEST(MethodsLineClip, NotesExampleLiangBarskyAndCyrusBeck) {
  const Rect2 window{3, 2, 7, 4};
  const m::LiangBarskyResult lb = m::clip_line_liang_barsky({{2, 3}, {8, 6}}, window);
  ASSERT_TRUE(lb.accepted);
  EXPECT_NEAR(lb.t_in, 1.0 / 6.0, 1e-15);   // x = 3
  EXPECT_NEAR(lb.t_out, 1.0 / 3.0, 1e-15);  // y = 4
  expect_point(lb.segment.p0, {3, 3.5});
  expect_point(lb.segment.p1, {4, 4});
  const m::CyrusBeckResult cb = m::clip_line_cyrus_beck({{2, 3}, {8, 6}}, m::rect_polygon(window));
  ASSERT_TRUE(cb.accepted);
  expect_point(cb.segment.p0, {3, 3.5});
  expect_point(cb.segment.p1, {4, 4});
}

// lecture-depth-clipping-polygon-offset.txt, "Exercise": left=-1, right=1, bottom=-1, top=1,
// clip P=(-1.5,-2) to Q=(0,0). The line is y = 4x/3: it meets y = -1 at x = -0.75 (inside
// -1..1) and x = -1 at y = -4/3 (below the window), so the answer is (-0.75,-1)-(0,0).
TEST(MethodsLineClip, Comp342Exercise) {
  const Rect2 window{-1, -1, 1, 1};
  const Segment2 pq{{-1.5, -2}, {0, 0}};
  const m::CohenSutherlandResult bottom_first = m::clip_line_cohen_sutherland(pq, window);
  ASSERT_TRUE(bottom_first.accepted);
  expect_point(bottom_first.segment.p0, {-0.75, -1});
  expect_point(bottom_first.segment.p1, {0, 0});
  EXPECT_EQ(bottom_first.clips, 1);
  EXPECT_EQ(bottom_first.passes, 2);

  // Picking the left edge first, as the notes' outcode bit order suggests, needs two cuts:
  // (-1, -4/3) is still below the window.
  m::CohenSutherlandOptions left_first;
  left_first.layout = m::OutcodeLayout::Comp342;
  left_first.side_order = {m::RectSide::XMin, m::RectSide::YMax, m::RectSide::XMax, m::RectSide::YMin};
  const m::CohenSutherlandResult r = m::clip_line_cohen_sutherland(pq, window, left_first);
  ASSERT_TRUE(r.accepted);
  expect_point(r.segment.p0, {-0.75, -1});
  EXPECT_EQ(r.clips, 2);
  EXPECT_EQ(r.passes, 3);

  const m::LiangBarskyResult lb = m::clip_line_liang_barsky(pq, window);
  ASSERT_TRUE(lb.accepted);
  EXPECT_DOUBLE_EQ(lb.t_in, 0.5);
  EXPECT_DOUBLE_EQ(lb.t_out, 1.0);
  expect_point(lb.segment.p0, {-0.75, -1});
}

// The nine regions, as the notes draw them (rows top to bottom, columns left to right).
TEST(MethodsLineClip, OutcodesOfTheNineRegions) {
  const Rect2 window{-1, -1, 1, 1};
  const double xs[3] = {-2, 0, 2}, ys[3] = {2, 0, -2};
  // notes-line-clipping-hidden-surface.txt Y0Y1X0X1 (Angel's b0b1b2b3).
  const uint8_t notes[3][3] = {{0b1001, 0b1000, 0b1010}, {0b0001, 0b0000, 0b0010}, {0b0101, 0b0100, 0b0110}};
  // lecture-depth-clipping-polygon-offset.txt "Labelling": 1100 0100 0110 / 1000 0000 0010 / 1001 0001 0011.
  const uint8_t comp342[3][3] = {{0b1100, 0b0100, 0b0110}, {0b1000, 0b0000, 0b0010}, {0b1001, 0b0001, 0b0011}};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      const Vec2 p{xs[col], ys[row]};
      EXPECT_EQ(m::outcode(p, window, m::OutcodeLayout::Notes), notes[row][col]) << "row " << row << " col " << col;
      EXPECT_EQ(m::outcode(p, window, m::OutcodeLayout::Comp342), comp342[row][col]) << "row " << row << " col " << col;
    }
  }
  // The window is closed: its sides and corners are inside.
  EXPECT_EQ(m::outcode({1, 1}, window), 0);
  EXPECT_EQ(m::outcode({-1, 0.5}, window), 0);
  // lecture-clipping-fill-zbuffer.txt "Example": A = 0001 (left), B = 0100 (bottom), A or B = 0101.
  EXPECT_EQ(m::outcode({-2, 0}, window) | m::outcode({0, -2}, window), 0b0101);
}

TEST(MethodsLineClip, TrivialAcceptAndReject) {
  const Rect2 window{0, 0, 10, 10};
  const m::CohenSutherlandResult in = m::clip_line_cohen_sutherland({{1, 1}, {9, 2}}, window);
  EXPECT_TRUE(in.accepted);
  EXPECT_EQ(in.passes, 1);
  EXPECT_EQ(in.clips, 0);
  const m::CohenSutherlandResult left = m::clip_line_cohen_sutherland({{-3, 1}, {-1, 9}}, window);
  EXPECT_FALSE(left.accepted);
  EXPECT_EQ(left.passes, 1);
  // Outside on different sides, AND == 0, yet missing the window: rejected after cutting.
  const m::CohenSutherlandResult miss = m::clip_line_cohen_sutherland({{-2, 9}, {2, 13}}, window);
  EXPECT_FALSE(miss.accepted);
  EXPECT_GE(miss.clips, 1);
  EXPECT_FALSE(m::clip_line_liang_barsky({{-2, 9}, {2, 13}}, window).accepted);
}

// lecture-depth-clipping-polygon-offset.txt "Case needing 4 Clips"; the rasterization lecture:
// "Using values of alpha, we do not have to use algorithm recursively as with C-S".
TEST(MethodsLineClip, CohenSutherlandNeedsFourClipsWhereLiangBarskyNeedsOnePass) {
  const Rect2 window{-1, -1, 1, 1};
  const Segment2 corner_to_corner{{-3, -1.5}, {3, 1.5}};  // y = x/2, from bottom-left to top-right region
  const m::CohenSutherlandResult cs = m::clip_line_cohen_sutherland(corner_to_corner, window);
  ASSERT_TRUE(cs.accepted);
  EXPECT_EQ(cs.clips, 4);   // bottom -> (-2,-1), left -> (-1,-0.5), top -> (2,1), right -> (1,0.5)
  EXPECT_EQ(cs.passes, 5);  // four cuts, then the trivial accept
  expect_point(cs.segment.p0, {-1, -0.5});
  expect_point(cs.segment.p1, {1, 0.5});
  const m::LiangBarskyResult lb = m::clip_line_liang_barsky(corner_to_corner, window);
  ASSERT_TRUE(lb.accepted);
  EXPECT_EQ(lb.sides_examined, 4);  // one pass over the four sides
  EXPECT_DOUBLE_EQ(lb.t_in, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(lb.t_out, 2.0 / 3.0);
  expect_point(lb.segment.p0, {-1, -0.5});
  expect_point(lb.segment.p1, {1, 0.5});
}

// lecture-depth-clipping-polygon-offset.txt "Cyrus Beck" "Example": the t_in / t_out table
//   0 1 / 0.1 1 / 0.1 0.9 / 0.1 0.85 / 0.1 0.85 / 0.2 0.85.
// The notes give only the table; this convex pentagon and the segment (0,0)-(10,0) reproduce it
// edge by edge: entering at 0.1, leaving at 0.9, leaving at 0.85, a parallel edge, entering at 0.2.
TEST(MethodsLineClip, CyrusBeckNotesTable) {
  const m::Polygon2 pentagon{{1.5, -1}, {2, -2}, {5.5, -1}, {11.5, 1}, {2.5, 1}};
  const m::CyrusBeckResult r = m::clip_line_cyrus_beck({{0, 0}, {10, 0}}, pentagon);
  ASSERT_EQ(r.trace.size(), 5u);
  const double table[5][2] = {{0.1, 1}, {0.1, 0.9}, {0.1, 0.85}, {0.1, 0.85}, {0.2, 0.85}};
  const m::CyrusBeckCrossing kinds[5] = {m::CyrusBeckCrossing::Entering, m::CyrusBeckCrossing::Leaving,
                                         m::CyrusBeckCrossing::Leaving, m::CyrusBeckCrossing::Parallel,
                                         m::CyrusBeckCrossing::Entering};
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(r.trace[i].edge, i);
    EXPECT_EQ(r.trace[i].crossing, kinds[i]) << "edge " << i;
    EXPECT_DOUBLE_EQ(r.trace[i].t_in, table[i][0]) << "edge " << i;
    EXPECT_DOUBLE_EQ(r.trace[i].t_out, table[i][1]) << "edge " << i;
  }
  ASSERT_TRUE(r.accepted);
  EXPECT_DOUBLE_EQ(r.t_in, 0.2);
  EXPECT_DOUBLE_EQ(r.t_out, 0.85);
  expect_point(r.segment.p0, {2, 0});
  expect_point(r.segment.p1, {8.5, 0});
  // The same window listed clockwise gives the same answer.
  const m::Polygon2 clockwise(pentagon.rbegin(), pentagon.rend());
  const m::CyrusBeckResult cw = m::clip_line_cyrus_beck({{0, 0}, {10, 0}}, clockwise);
  ASSERT_TRUE(cw.accepted);
  EXPECT_DOUBLE_EQ(cw.t_in, 0.2);
  EXPECT_DOUBLE_EQ(cw.t_out, 0.85);
}

// The notes' pseudocode skips parallel edges ("Ignore edges parallel to line"); a short segment
// above the pentagon, parallel to its top edge and inside every other edge's half-plane, would be
// accepted. The module rejects it.
TEST(MethodsLineClip, CyrusBeckRejectsParallelSegmentOutside) {
  const m::Polygon2 pentagon{{1.5, -1}, {2, -2}, {5.5, -1}, {11.5, 1}, {2.5, 1}};
  const m::CyrusBeckResult r = m::clip_line_cyrus_beck({{5, 5}, {6, 5}}, pentagon);
  EXPECT_FALSE(r.accepted);
  EXPECT_LE(r.t_in, r.t_out);  // what skipping the parallel edge alone would have accepted
}

TEST(MethodsLineClip, CyrusBeckPointAndBadWindow) {
  const m::Polygon2 square = m::rect_polygon({0, 0, 1, 1});
  EXPECT_TRUE(m::clip_line_cyrus_beck({{0.5, 0.5}, {0.5, 0.5}}, square).accepted);
  EXPECT_FALSE(m::clip_line_cyrus_beck({{2, 0.5}, {2, 0.5}}, square).accepted);
  const m::Polygon2 concave{{0, 0}, {4, 0}, {4, 4}, {2, 1}, {0, 4}};
  EXPECT_THROW(m::clip_line_cyrus_beck({{0, 0}, {1, 1}}, concave), std::invalid_argument);
  const m::Polygon2 pentagram{{0, 1}, {0.588, -0.809}, {-0.951, 0.309}, {0.951, 0.309}, {-0.588, -0.809}};
  EXPECT_THROW(m::clip_line_cyrus_beck({{0, 0}, {1, 1}}, pentagram), std::invalid_argument);
}

TEST(MethodsLineClip, CohenSutherland3dOutcodesAndBox) {
  const m::ClipVolume box = m::box_volume({-1, -1, -1, 1, 1, 1});
  EXPECT_EQ(m::outcode(box, {0, 0, 0, 1}), 0);
  EXPECT_EQ(m::outcode(box, {-2, 0, 0, 1}), 1);
  EXPECT_EQ(m::outcode(box, {2, 0, 0, 1}), 2);
  EXPECT_EQ(m::outcode(box, {0, -2, 0, 1}), 4);
  EXPECT_EQ(m::outcode(box, {0, 2, 0, 1}), 8);
  EXPECT_EQ(m::outcode(box, {0, 0, -2, 1}), 16);
  EXPECT_EQ(m::outcode(box, {0, 0, 2, 1}), 32);
  EXPECT_EQ(m::outcode(box, {-2, 2, 2, 1}), 1 | 8 | 32);
  // x = -3 + 6t is inside for t in [1/3, 2/3], z = -0.5 + 3t for t in [1/6, 1/2]: visible t in [1/3, 1/2].
  const m::CohenSutherland3dResult r =
      m::clip_line_cohen_sutherland_box({-3, 0, -0.5}, {3, 0.6, 2.5}, {-1, -1, -1, 1, 1, 1});
  ASSERT_TRUE(r.accepted);
  // p0 is outside x low and z low: cutting at x low (the lower bit) lands at z = 0.5, inside.
  // p1 is outside x high and z high: x high first lands at (1, 0.4, 1.5), then z high.
  EXPECT_EQ(r.clips, 3);
  EXPECT_EQ(r.passes, 4);
  EXPECT_NEAR(r.p0.x, -1, 1e-12);
  EXPECT_NEAR(r.p0.y, 0.2, 1e-12);
  EXPECT_NEAR(r.p0.z, 0.5, 1e-12);
  EXPECT_NEAR(r.p1.x, 0, 1e-12);
  EXPECT_NEAR(r.p1.y, 0.3, 1e-12);
  EXPECT_NEAR(r.p1.z, 1, 1e-12);
  EXPECT_DOUBLE_EQ(r.p0.w, 1);
}

// Homogeneous clipping before the divide: w varies along the segment.
TEST(MethodsLineClip, CohenSutherland3dHomogeneous) {
  const m::ClipVolume vulkan = m::homogeneous_volume(m::ClipDepthRange::ZeroToOne);
  // x = 4t, w = 1 + t: x <= w until t = 1/3, where the point is (4/3, 0, 0.5, 4/3).
  const m::CohenSutherland3dResult r = m::clip_line_cohen_sutherland_3d({0, 0, 0.5, 1}, {4, 0, 0.5, 2}, vulkan);
  ASSERT_TRUE(r.accepted);
  EXPECT_EQ(r.clips, 1);
  EXPECT_NEAR(r.p1.x, 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(r.p1.w, 4.0 / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(r.p1.x, r.p1.w);  // snapped exactly onto x = w
  // z in -w..w (OpenGL) keeps z = -0.5 w; 0..w (Vulkan) cuts it.
  const m::ClipVolume opengl = m::homogeneous_volume(m::ClipDepthRange::MinusOneToOne);
  EXPECT_EQ(m::outcode(opengl, {0, 0, -0.5, 1}), 0);
  EXPECT_EQ(m::outcode(vulkan, {0, 0, -0.5, 1}), 16);
  // Behind the eye (w < 0) nothing is inside.
  EXPECT_NE(m::outcode(vulkan, {0, 0, 0, -1}), 0);
}

// All rectangle clippers agree within float tolerance (a grazing segment may be a point for one
// and rejected by another).
RC_GTEST_PROP(MethodsLineClipProperty, ClippersAgree, ()) {
  const Rect2 window = random_window();
  const Segment2 s = random_segment();
  const m::CohenSutherlandResult cs = m::clip_line_cohen_sutherland(s, window);
  const m::LiangBarskyResult lb = m::clip_line_liang_barsky(s, window);
  const m::CyrusBeckResult cb = m::clip_line_cyrus_beck(s, m::rect_polygon(window));
  const m::CohenSutherland3dResult cs3 = m::clip_line_cohen_sutherland_box(
      {s.p0.x, s.p0.y, 0}, {s.p1.x, s.p1.y, 0}, {window.x_min, window.y_min, -1, window.x_max, window.y_max, 1});
  const Segment2 cs3_segment{{cs3.p0.x, cs3.p0.y}, {cs3.p1.x, cs3.p1.y}};
  const bool all_agree = cs.accepted == lb.accepted && lb.accepted == cb.accepted && cb.accepted == cs3.accepted;
  if (!all_agree) {  // only a point-sized visible part may be accepted by some and rejected by others
    if (cs.accepted) RC_ASSERT(length(cs.segment) < 1e-9);
    if (lb.accepted) RC_ASSERT(length(lb.segment) < 1e-9);
    if (cb.accepted) RC_ASSERT(length(cb.segment) < 1e-9);
    if (cs3.accepted) RC_ASSERT(length(cs3_segment) < 1e-9);
    return;
  }
  if (!lb.accepted) return;
  for (const Segment2& other : {cs.segment, cb.segment, cs3_segment}) {
    RC_ASSERT(std::fabs(other.p0.x - lb.segment.p0.x) < kTol && std::fabs(other.p0.y - lb.segment.p0.y) < kTol);
    RC_ASSERT(std::fabs(other.p1.x - lb.segment.p1.x) < kTol && std::fabs(other.p1.y - lb.segment.p1.y) < kTol);
  }
}

// The clipped part lies inside the window and on the original segment.
RC_GTEST_PROP(MethodsLineClipProperty, ClippedSegmentInsideWindowAndOnLine, ()) {
  const Rect2 window = random_window();
  const Segment2 s = random_segment();
  RC_PRE(length(s) > 1e-6);
  const m::CohenSutherlandResult cs = m::clip_line_cohen_sutherland(s, window);
  const m::LiangBarskyResult lb = m::clip_line_liang_barsky(s, window);
  for (const auto& [accepted, part] : {std::pair{cs.accepted, cs.segment}, std::pair{lb.accepted, lb.segment}}) {
    if (!accepted) continue;
    RC_ASSERT(inside(part.p0, window, kTol));
    RC_ASSERT(inside(part.p1, window, kTol));
    RC_ASSERT(distance_to_line(part.p0, s) < kTol);
    RC_ASSERT(distance_to_line(part.p1, s) < kTol);
  }
  if (lb.accepted) RC_ASSERT(0 <= lb.t_in && lb.t_in <= lb.t_out && lb.t_out <= 1);
  // A window that contains both ends: accepted unchanged.
  if (inside(s.p0, window, 0) && inside(s.p1, window, 0)) {
    RC_ASSERT(cs.accepted && cs.segment.p0 == s.p0 && cs.segment.p1 == s.p1);
    RC_ASSERT(cs.passes == 1);
  }
}

// Cyrus–Beck against a random convex window: points of the segment are inside exactly for
// t in [t_in, t_out] (checked away from the two crossings).
RC_GTEST_PROP(MethodsLineClipProperty, CyrusBeckMatchesInsideTest, ()) {
  const size_t n = *rc::gen::resize(100, rc::gen::inRange<size_t>(3, 9));
  const Vec2 centre{*coordinate(-3, 3), *coordinate(-3, 3)};
  const double radius = *coordinate(1, 6);
  m::Polygon2 window;
  for (size_t i = 0; i < n; ++i) {
    const double angle = 6.283185307179586 * (double(i) + *coordinate(0, 0.8)) / double(n);
    window.push_back({centre.x + radius * std::cos(angle), centre.y + radius * std::sin(angle)});
  }
  const Segment2 s = random_segment();
  RC_PRE(length(s) > 1e-6);
  const m::CyrusBeckResult r = m::clip_line_cyrus_beck(s, window);
  for (int k = 0; k <= 64; ++k) {
    const double t = k / 64.0;
    const Vec2 p = m::lerp(s.p0, s.p1, t);
    const bool in_window = m::winding_number(window, p) != 0;
    const bool in_range = r.accepted && t >= r.t_in && t <= r.t_out;
    const double margin = 1e-7;
    const bool near_crossing = std::fabs(t - r.t_in) < margin || std::fabs(t - r.t_out) < margin;
    if (!near_crossing) RC_ASSERT(in_window == in_range);
  }
}

// For points with w = 1 the homogeneous Vulkan volume is the box [-1,1]^2 x [0,1].
RC_GTEST_PROP(MethodsLineClipProperty, HomogeneousEqualsBoxForUnitW, ()) {
  const m::Vec3 a{*coordinate(-3, 3), *coordinate(-3, 3), *coordinate(-2, 3)};
  const m::Vec3 b{*coordinate(-3, 3), *coordinate(-3, 3), *coordinate(-2, 3)};
  const m::CohenSutherland3dResult h = m::clip_line_cohen_sutherland_3d(
      {a.x, a.y, a.z, 1}, {b.x, b.y, b.z, 1}, m::homogeneous_volume(m::ClipDepthRange::ZeroToOne));
  const m::CohenSutherland3dResult box = m::clip_line_cohen_sutherland_box(a, b, {-1, -1, 0, 1, 1, 1});
  RC_ASSERT(h.accepted == box.accepted);
  RC_ASSERT(h.passes == box.passes);
  if (!h.accepted) return;
  RC_ASSERT(h.p0 == box.p0);
  RC_ASSERT(h.p1 == box.p1);
  for (const m::Vec4& p : {h.p0, h.p1}) {
    RC_ASSERT(m::outcode(m::homogeneous_volume(m::ClipDepthRange::ZeroToOne), p) == 0);
  }
}
