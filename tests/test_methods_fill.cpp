// Fill methods: the notes' scanline fill, even-odd / non-zero fill, the float edge-function fill
// (with and without the top-left rule) and flood fill.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "cpu_raster/methods/fill_edge_function.hpp"
#include "cpu_raster/methods/fill_flood.hpp"
#include "cpu_raster/methods/fill_polygon_rule.hpp"
#include "cpu_raster/methods/fill_scanline_notes.hpp"
#include "cpu_raster/methods/line_bresenham.hpp"

namespace m = rastercmp::methods;
using m::PixelXY;
using m::Polygon2;
using m::Span;

namespace {

std::set<PixelXY> pixel_set(const std::vector<Span>& spans) {
  const std::vector<PixelXY> pixels = m::spans_to_pixels(spans);
  return {pixels.begin(), pixels.end()};
}

// lecture-clipping-fill-zbuffer.txt "Polygon Filling Illustrated": the polygon whose scanline
// intersections the notes list, (3,0) at the bottom, a V notch (3,2) at the top.
const Polygon2 kNotesPolygon{{3, 0}, {6, 2}, {6, 4}, {3, 2}, {0, 4}, {0, 2}};

// A value on a half-pixel grid in [0, 16]: pixel centres often lie exactly on edges, and every
// float computation of the fills is exact.
rc::Gen<double> half_grid() {
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange(0, 33)), [](int k) { return k * 0.5; });
}
rc::Gen<double> coordinate(double lo, double hi) {
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange<int64_t>(0, int64_t(1) << 20)),
                      [=](int64_t k) { return lo + (hi - lo) * double(k) / double(int64_t(1) << 20); });
}

Polygon2 random_star(size_t max_vertices) {
  const size_t n = *rc::gen::resize(100, rc::gen::inRange<size_t>(3, max_vertices + 1));
  const m::Vec2 centre{*coordinate(8, 24), *coordinate(8, 24)};
  const double r_max = *coordinate(2, 12);
  Polygon2 polygon;
  for (size_t i = 0; i < n; ++i) {
    const double angle = 6.283185307179586 * (double(i) + *coordinate(0, 0.8)) / double(n);
    const double r = r_max * *coordinate(0.2, 1);
    polygon.push_back({centre.x + r * std::cos(angle), centre.y + r * std::sin(angle)});
  }
  return polygon;
}

m::PolygonFillOptions rule_options(m::FillRule rule, double offset) {
  m::PolygonFillOptions options;
  options.rule = rule;
  options.sample_offset = offset;
  return options;
}

}  // namespace

// The notes' intersections after "ignore horizontal boundaries" and "open at the top": the row
// y = 4 is struck out (only tops of edges), y = 2 keeps (0,2) (3,2) (3,2) (6,2).
TEST(MethodsFill, NotesPolygonIntersections) {
  using V = std::vector<double>;
  EXPECT_EQ(m::scanline_intersections_notes(kNotesPolygon, 0), (V{3, 3}));
  EXPECT_EQ(m::scanline_intersections_notes(kNotesPolygon, 1), (V{1.5, 4.5}));
  EXPECT_EQ(m::scanline_intersections_notes(kNotesPolygon, 2), (V{0, 3, 3, 6}));
  EXPECT_EQ(m::scanline_intersections_notes(kNotesPolygon, 3), (V{0, 1.5, 4.5, 6}));
  EXPECT_EQ(m::scanline_intersections_notes(kNotesPolygon, 4), (V{}));
}

// "Final Result": (2,1)-(5,1) after rounding up fills x = 2, 3, 4; (0,2)-(3,2), (3,2)-(6,2) fill
// the whole row; (0,3)-(2,3), (5,3)-(6,3) fill x = 0, 1 and 5; the "Maybe" vertex (3,0)-(3,0) is
// an empty pair, so the pseudo-code does not fill it.
TEST(MethodsFill, NotesPolygonFilledPixels) {
  const std::set<PixelXY> expected{{2, 1}, {3, 1}, {4, 1}, {0, 2}, {1, 2}, {2, 2},
                                   {3, 2}, {4, 2}, {5, 2}, {0, 3}, {1, 3}, {5, 3}};
  EXPECT_EQ(pixel_set(m::fill_scanline_notes(kNotesPolygon)), expected);
  // The same pixels as the even-odd rule sampled at integer points.
  EXPECT_EQ(pixel_set(m::fill_polygon_rule(kNotesPolygon, rule_options(m::FillRule::EvenOdd, 0))), expected);
}

// "Which pixels should be filled in? ... What happened to the top pixels? To the rightmost
// pixels?": left and lower boundaries are filled, right and upper are not, so two rectangles
// sharing a side never double-fill.
TEST(MethodsFill, NotesRectangleRule) {
  const Polygon2 left{{0, 0}, {4, 0}, {4, 3}, {0, 3}}, right{{4, 0}, {8, 0}, {8, 3}, {4, 3}};
  const std::vector<Span> spans = m::fill_scanline_notes(left);
  EXPECT_EQ(spans, (std::vector<Span>{{0, 0, 4}, {1, 0, 4}, {2, 0, 4}}));  // no row 3, no column 4
  const std::vector<uint32_t> counts = m::coverage_counts({spans, m::fill_scanline_notes(right)}, 9, 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 9; ++x) EXPECT_EQ(counts[size_t(y * 9 + x)], (x < 8 && y < 3) ? 1u : 0u) << x << "," << y;
  }
  // Bounds clamp the spans.
  EXPECT_EQ(m::fill_scanline_notes(left, {1, 1, 3, 2}), (std::vector<Span>{{1, 1, 3}}));
}

// A pentagram: the centre has winding number 2 — filled by non-zero, a hole for even-odd.
TEST(MethodsFill, PentagramWindingVersusEvenOdd) {
  Polygon2 star;
  for (int k = 0; k < 5; ++k) {
    const double angle = 1.5707963267948966 + 2 * 6.283185307179586 * k / 5;
    star.push_back({16 + 12 * std::cos(angle), 16 + 12 * std::sin(angle)});
  }
  const std::set<PixelXY> non_zero = pixel_set(m::fill_polygon_rule(star, rule_options(m::FillRule::NonZero, 0.5)));
  const std::set<PixelXY> even_odd = pixel_set(m::fill_polygon_rule(star, rule_options(m::FillRule::EvenOdd, 0.5)));
  EXPECT_TRUE(non_zero.count({15, 15}));
  EXPECT_FALSE(even_odd.count({15, 15}));
  EXPECT_TRUE(std::includes(non_zero.begin(), non_zero.end(), even_odd.begin(), even_odd.end()));
  EXPECT_GT(non_zero.size(), even_odd.size());
  EXPECT_EQ(m::winding_number(star, {15.5, 15.5}), 2);
}

// Pinned: two triangles sharing the diagonal x + y = 4, which passes through the centres of
// (0,3), (1,2), (2,1), (3,0). The textbook float test (all E >= 0) fills those four twice; the
// top-left rule fills every pixel of the square exactly once.
TEST(MethodsFill, FloatEdgeFillDoubleCoversSharedEdge) {
  const std::array<m::Vec2f, 3> lower{{{0, 0}, {4, 0}, {0, 4}}}, upper{{{4, 0}, {4, 4}, {0, 4}}};
  const std::vector<uint32_t> textbook =
      m::coverage_counts({m::fill_triangle_edge_function(lower, m::EdgeTieRule::None),
                          m::fill_triangle_edge_function(upper, m::EdgeTieRule::None)},
                         4, 4);
  const std::vector<uint32_t> top_left =
      m::coverage_counts({m::fill_triangle_edge_function(lower, m::EdgeTieRule::TopLeft),
                          m::fill_triangle_edge_function(upper, m::EdgeTieRule::TopLeft)},
                         4, 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const size_t i = size_t(y * 4 + x);
      EXPECT_EQ(textbook[i], x + y == 3 ? 2u : 1u) << x << "," << y;
      EXPECT_EQ(top_left[i], 1u) << x << "," << y;
    }
  }
  EXPECT_EQ(m::edge_function({0, 4}, {4, 0}, {1.5f, 2.5f}), 0.0f);
  // Winding order does not matter; a zero-area triangle covers nothing.
  const std::array<m::Vec2f, 3> lower_cw{{{0, 0}, {0, 4}, {4, 0}}};
  EXPECT_EQ(m::fill_triangle_edge_function(lower_cw, m::EdgeTieRule::TopLeft),
            m::fill_triangle_edge_function(lower, m::EdgeTieRule::TopLeft));
  EXPECT_TRUE(m::fill_triangle_edge_function({{{0, 0}, {2, 2}, {4, 4}}}, m::EdgeTieRule::None).empty());
}

// The notes' flood_fill: 4-connected, so a Bresenham diagonal (8-connected) is a wall; with
// 8-connectivity the fill leaks through it.
TEST(MethodsFill, FloodFillFourVersusEightConnected) {
  m::CellGrid grid{10, 10, std::vector<uint32_t>(100, 0)};
  for (const PixelXY& p : m::line_bresenham({0, 0}, {9, 9})) grid.cells[size_t(p.y * 10 + p.x)] = 1;
  const m::FloodFillResult four = m::flood_fill(grid, {9, 0}, 2, m::Connectivity::Four);
  EXPECT_EQ(four.filled, 45u);  // the cells with x > y
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) {
      EXPECT_EQ(four.grid.at({x, y}), x > y ? 2u : (x == y ? 1u : 0u)) << x << "," << y;
    }
  }
  EXPECT_EQ(m::flood_fill(grid, {9, 0}, 2, m::Connectivity::Eight).filled, 90u);
  EXPECT_EQ(m::flood_fill(grid, {9, 0}, 0).filled, 0u);   // already the replacement
  EXPECT_EQ(m::flood_fill(grid, {10, 0}, 2).filled, 0u);  // outside the grid
  EXPECT_EQ(grid.at({9, 0}), 0u);                         // the input is untouched
}

// Iterative: a region far too large for recursion.
TEST(MethodsFill, FloodFillLargeRegion) {
  const m::CellGrid grid{1024, 1024, std::vector<uint32_t>(1024 * 1024, 7)};
  const m::FloodFillResult r = m::flood_fill(grid, {750, 750}, 3);
  EXPECT_EQ(r.filled, 1024u * 1024u);
  EXPECT_TRUE(std::all_of(r.grid.cells.begin(), r.grid.cells.end(), [](uint32_t c) { return c == 3; }));
}

// The notes' fill is the even-odd rule at integer sample points, also for self-intersecting loops.
RC_GTEST_PROP(MethodsFillProperty, NotesFillIsEvenOddAtIntegerPoints, ()) {
  const size_t n = *rc::gen::resize(100, rc::gen::inRange<size_t>(3, 9));
  Polygon2 polygon;
  for (size_t i = 0; i < n; ++i) polygon.push_back({*coordinate(0, 24), *coordinate(0, 24)});
  RC_ASSERT(pixel_set(m::fill_scanline_notes(polygon)) ==
            pixel_set(m::fill_polygon_rule(polygon, rule_options(m::FillRule::EvenOdd, 0))));
}

// On simple polygons the winding and even-odd rules agree.
RC_GTEST_PROP(MethodsFillProperty, WindingAndEvenOddAgreeOnSimplePolygons, ()) {
  const Polygon2 polygon = random_star(16);
  const double offset = *rc::gen::element(0.0, 0.5);
  RC_ASSERT(pixel_set(m::fill_polygon_rule(polygon, rule_options(m::FillRule::NonZero, offset))) ==
            pixel_set(m::fill_polygon_rule(polygon, rule_options(m::FillRule::EvenOdd, offset))));
}

// Two triangles sharing an edge, vertices on a half-pixel grid (so centres often lie on edges):
// the top-left float fill never covers a pixel twice and equals the half-open scanline rule
// (both are the top-left rule in y-down coordinates), and each triangle's top-left coverage is
// a subset of its textbook (E >= 0) coverage.
RC_GTEST_PROP(MethodsFillProperty, TopLeftFillCoversSharedEdgesOnce, ()) {
  const m::Vec2f a{float(*half_grid()), float(*half_grid())}, b{float(*half_grid()), float(*half_grid())};
  const m::Vec2f c{float(*half_grid()), float(*half_grid())}, d{float(*half_grid()), float(*half_grid())};
  const std::array<m::Vec2f, 3> t1{a, b, c}, t2{b, a, d};  // share edge a-b
  const float side_c = m::edge_function(a, b, c), side_d = m::edge_function(a, b, d);
  RC_PRE((side_c > 0 && side_d < 0) || (side_c < 0 && side_d > 0));  // on opposite sides of a-b
  const std::vector<Span> s1 = m::fill_triangle_edge_function(t1, m::EdgeTieRule::TopLeft);
  const std::vector<Span> s2 = m::fill_triangle_edge_function(t2, m::EdgeTieRule::TopLeft);
  for (uint32_t count : m::coverage_counts({s1, s2}, 17, 17)) RC_ASSERT(count <= 1u);
  for (const auto& [t, s] : {std::pair{t1, s1}, std::pair{t2, s2}}) {
    const std::set<PixelXY> tl = pixel_set(s),
                            textbook = pixel_set(m::fill_triangle_edge_function(t, m::EdgeTieRule::None));
    RC_ASSERT(std::includes(textbook.begin(), textbook.end(), tl.begin(), tl.end()));
    const Polygon2 polygon{{t[0].x, t[0].y}, {t[1].x, t[1].y}, {t[2].x, t[2].y}};
    RC_ASSERT(tl == pixel_set(m::fill_polygon_rule(polygon, rule_options(m::FillRule::NonZero, 0.5))));
  }
}
