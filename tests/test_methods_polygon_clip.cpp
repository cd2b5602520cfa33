// Polygon clipping methods: Sutherland–Hodgman (2D and homogeneous) and Weiler–Atherton.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cpu_raster/methods/clip_polygon_sutherland_hodgman.hpp"
#include "cpu_raster/methods/clip_polygon_weiler_atherton.hpp"

namespace m = rastercmp::methods;
using m::Polygon2;
using m::Vec2;

namespace {

constexpr double kTwoPi = 6.283185307179586;

// Uniform over the whole range at every test size (rapidcheck scales inRange by size otherwise).
rc::Gen<double> coordinate(double lo, double hi) {
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange<int64_t>(0, int64_t(1) << 20)),
                      [=](int64_t k) { return lo + (hi - lo) * double(k) / double(int64_t(1) << 20); });
}

// Simple by construction: vertices at increasing angles around a centre (star-shaped), concave
// when the radii vary. `convex` puts them all on one circle.
Polygon2 random_star(size_t max_vertices, bool convex) {
  const size_t n = *rc::gen::resize(100, rc::gen::inRange<size_t>(3, max_vertices + 1));
  const Vec2 centre{*coordinate(-1.5, 1.5), *coordinate(-1.5, 1.5)};
  const double r_max = *coordinate(2, 6);
  Polygon2 polygon;
  for (size_t i = 0; i < n; ++i) {
    const double angle = kTwoPi * (double(i) + *coordinate(0, 0.8)) / double(n);
    const double r = convex ? r_max : r_max * *coordinate(0.15, 1);
    polygon.push_back({centre.x + r * std::cos(angle), centre.y + r * std::sin(angle)});
  }
  return polygon;
}

double total_area(const std::vector<Polygon2>& polygons) {
  double sum = 0;
  for (const Polygon2& p : polygons) sum += std::fabs(m::signed_area(p));
  return sum;
}

double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double t = std::clamp(m::dot(p - a, d) / m::dot(d, d), 0.0, 1.0);
  const Vec2 q = m::lerp(a, b, t);
  return std::hypot(p.x - q.x, p.y - q.y);
}

double distance_to_boundary(Vec2 p, const Polygon2& polygon) {
  double best = INFINITY;
  for (size_t i = 0; i < polygon.size(); ++i) {
    best = std::min(best, distance_to_segment(p, polygon[i], polygon[(i + 1) % polygon.size()]));
  }
  return best;
}

bool inside_any(const std::vector<Polygon2>& polygons, Vec2 p) {
  bool inside = false;
  for (const Polygon2& polygon : polygons) inside = inside != m::inside_even_odd(polygon, p);
  return inside;
}

// The U of the Weiler–Atherton examples: arms x in [0,2] and [4,6] over y in [2,6], base y in [0,2].
const Polygon2 kU{{0, 0}, {6, 0}, {6, 6}, {4, 6}, {4, 2}, {2, 2}, {2, 6}, {0, 6}};

}  // namespace

TEST(MethodsPolygonClip, SutherlandHodgmanTriangleInSquare) {
  const Polygon2 triangle{{0, 0}, {4, 0}, {0, 4}};
  const Polygon2 out = m::clip_polygon_sutherland_hodgman(triangle, m::Rect2{1, 1, 3, 3});
  // The square minus the corner beyond x + y = 4: the triangle (1,1), (3,1), (1,3).
  EXPECT_NEAR(m::signed_area(out), 2.0, 1e-12);
  for (const Vec2& v : out) {
    EXPECT_GE(v.x, 1 - 1e-12);
    EXPECT_LE(v.x + v.y, 4 + 1e-12);
  }
  EXPECT_TRUE(m::clip_polygon_sutherland_hodgman(triangle, m::Rect2{5, 5, 6, 6}).empty());
  const Polygon2 whole = m::clip_polygon_sutherland_hodgman(triangle, m::Rect2{-1, -1, 5, 5});
  EXPECT_EQ(whole.size(), 3u);
  EXPECT_DOUBLE_EQ(m::signed_area(whole), 8.0);
}

// A concave subject whose clipped part falls apart: one output loop with a zero-area bridge,
// whose area is still the area of the two pieces.
TEST(MethodsPolygonClip, SutherlandHodgmanConcaveSubjectBridges) {
  const Polygon2 out = m::clip_polygon_sutherland_hodgman(kU, m::Rect2{-1, 3, 7, 5});
  EXPECT_NEAR(m::signed_area(out), 8.0, 1e-12);  // [0,2]x[3,5] and [4,6]x[3,5]
  const m::WeilerAthertonResult wa = m::clip_polygon_weiler_atherton(kU, m::rect_polygon({-1, 3, 7, 5}));
  ASSERT_FALSE(wa.degenerate);
  EXPECT_EQ(wa.polygons.size(), 2u);  // Weiler–Atherton returns the two pieces separately
  EXPECT_NEAR(total_area(wa.polygons), 8.0, 1e-12);
}

// Concave against concave: the U against a comb with two teeth crossing both arms gives four
// separate 2 x 0.5 rectangles.
TEST(MethodsPolygonClip, WeilerAthertonConcaveAgainstConcave) {
  const Polygon2 comb{{-1, 3}, {7, 3}, {7, 3.5}, {-0.5, 3.5}, {-0.5, 4.5}, {7, 4.5}, {7, 5}, {-1, 5}};
  const m::WeilerAthertonResult r = m::clip_polygon_weiler_atherton(kU, comb);
  ASSERT_FALSE(r.degenerate);
  EXPECT_EQ(r.crossings, 16u);
  ASSERT_EQ(r.polygons.size(), 4u);
  for (const Polygon2& piece : r.polygons) {
    EXPECT_EQ(piece.size(), 4u);
    EXPECT_NEAR(m::signed_area(piece), 1.0, 1e-12);  // counter-clockwise
  }
  // Clipping the comb by the U gives the same region.
  const m::WeilerAthertonResult swapped = m::clip_polygon_weiler_atherton(comb, kU);
  ASSERT_FALSE(swapped.degenerate);
  EXPECT_EQ(swapped.polygons.size(), 4u);
  EXPECT_NEAR(total_area(swapped.polygons), 4.0, 1e-12);
}

TEST(MethodsPolygonClip, WeilerAthertonWithoutCrossings) {
  const Polygon2 big = m::rect_polygon({-10, -10, 10, 10});
  const Polygon2 small{{1, 1}, {2, 1}, {1.5, 2}};
  const Polygon2 far{{20, 20}, {21, 20}, {20, 21}};
  ASSERT_EQ(m::clip_polygon_weiler_atherton(small, big).polygons.size(), 1u);
  EXPECT_EQ(m::clip_polygon_weiler_atherton(small, big).polygons[0], small);
  ASSERT_EQ(m::clip_polygon_weiler_atherton(big, small).polygons.size(), 1u);
  EXPECT_EQ(m::clip_polygon_weiler_atherton(big, small).polygons[0], small);
  EXPECT_TRUE(m::clip_polygon_weiler_atherton(small, far).polygons.empty());
  // Clockwise input comes back counter-clockwise.
  const Polygon2 clockwise(small.rbegin(), small.rend());
  EXPECT_GT(m::signed_area(m::clip_polygon_weiler_atherton(clockwise, big).polygons.at(0)), 0);
}

TEST(MethodsPolygonClip, WeilerAthertonReportsDegenerateContact) {
  const Polygon2 square = m::rect_polygon({0, 0, 2, 2});
  const Polygon2 touching{{2, 1}, {4, 0}, {4, 2}};  // a vertex on the square's right side
  const m::WeilerAthertonResult r = m::clip_polygon_weiler_atherton(touching, square);
  EXPECT_TRUE(r.degenerate);
  EXPECT_TRUE(r.polygons.empty());
  const Polygon2 sharing_edge = m::rect_polygon({2, 0, 4, 2});
  EXPECT_TRUE(m::clip_polygon_weiler_atherton(sharing_edge, square).degenerate);
  EXPECT_THROW(m::clip_polygon_weiler_atherton({{0, 0}, {1, 1}}, square), std::invalid_argument);
}

// Homogeneous clipping: a triangle through the near plane z = 0 of Vulkan clip space.
TEST(MethodsPolygonClip, SutherlandHodgmanHomogeneousNearPlane) {
  const std::vector<m::Vec4> triangle{{0, 0, -0.5, 1}, {0.5, 0, 0.5, 1}, {0, 0.5, 0.5, 1}};
  const m::ClipVolume vulkan = m::homogeneous_volume(m::ClipDepthRange::ZeroToOne);
  const std::vector<m::Vec4> out = m::clip_polygon_sutherland_hodgman(triangle, vulkan);
  ASSERT_EQ(out.size(), 4u);  // one vertex cut off: a quad
  for (const m::Vec4& v : out) EXPECT_EQ(m::outcode(vulkan, v), 0);
  // In -w..w (OpenGL) the triangle is already inside.
  EXPECT_EQ(m::clip_polygon_sutherland_hodgman(triangle, m::homogeneous_volume(m::ClipDepthRange::MinusOneToOne)),
            triangle);
  // Entirely behind the eye: nothing.
  const std::vector<m::Vec4> behind{{0, 0, 0.5, -1}, {0.5, 0, 0.5, -1}, {0, 0.5, 0.5, -1}};
  EXPECT_TRUE(m::clip_polygon_sutherland_hodgman(behind, vulkan).empty());
}

TEST(MethodsPolygonClip, SutherlandHodgmanRejectsConcaveWindow) {
  EXPECT_THROW(m::clip_polygon_sutherland_hodgman(m::rect_polygon({0, 0, 1, 1}), kU), std::invalid_argument);
}

// Output inside the convex window; its area no more than the input's.
RC_GTEST_PROP(MethodsPolygonClipProperty, SutherlandHodgmanInsideAndSmaller, ()) {
  const Polygon2 subject = random_star(10, false);
  const Polygon2 window = random_star(8, true);
  const Polygon2 out = m::clip_polygon_sutherland_hodgman(subject, window);
  const double orientation = m::signed_area(window) > 0 ? 1 : -1;
  for (const Vec2& v : out) {
    for (size_t i = 0; i < window.size(); ++i) {
      const Vec2 a = window[i], b = window[(i + 1) % window.size()];
      RC_ASSERT(orientation * m::cross(b - a, v - a) >= -1e-9);
    }
  }
  RC_ASSERT(std::fabs(m::signed_area(out)) <= std::fabs(m::signed_area(subject)) + 1e-9);
  RC_ASSERT(std::fabs(m::signed_area(out)) <= std::fabs(m::signed_area(window)) + 1e-9);
}

// With a convex clip region Weiler–Atherton's pieces cover the same area as Sutherland–Hodgman's
// single (possibly bridged) loop.
RC_GTEST_PROP(MethodsPolygonClipProperty, WeilerAthertonAreaEqualsSutherlandHodgman, ()) {
  const Polygon2 subject = random_star(10, false);
  const Polygon2 window = random_star(8, true);
  const m::WeilerAthertonResult wa = m::clip_polygon_weiler_atherton(subject, window);
  RC_PRE(!wa.degenerate);
  const Polygon2 sh = m::clip_polygon_sutherland_hodgman(subject, window);
  RC_ASSERT(std::fabs(total_area(wa.polygons) - std::fabs(m::signed_area(sh))) < 1e-8);
}

// Concave against concave: a point is in the output exactly when it is in both polygons
// (sample points closer than 1e-6 to any boundary are skipped).
RC_GTEST_PROP(MethodsPolygonClipProperty, WeilerAthertonIsTheIntersection, ()) {
  const Polygon2 subject = random_star(24, false);
  const Polygon2 clip = random_star(24, false);
  const m::WeilerAthertonResult r = m::clip_polygon_weiler_atherton(subject, clip);
  RC_PRE(!r.degenerate);
  RC_TAG(r.polygons.size());  // the distribution of piece counts is printed
  for (const Polygon2& piece : r.polygons) RC_ASSERT(m::signed_area(piece) > 0);
  RC_ASSERT(total_area(r.polygons) <=
            std::min(std::fabs(m::signed_area(subject)), std::fabs(m::signed_area(clip))) + 1e-9);
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 40; ++j) {
      const Vec2 p{-9.3 + 0.4567 * i, -9.1 + 0.4519 * j};
      if (distance_to_boundary(p, subject) < 1e-6 || distance_to_boundary(p, clip) < 1e-6) continue;
      const bool expected = m::inside_even_odd(subject, p) && m::inside_even_odd(clip, p);
      RC_ASSERT(inside_any(r.polygons, p) == expected);
    }
  }
}

// Points with w = 1 and z inside the depth range: homogeneous clipping is 2D clipping to [-1,1]^2.
RC_GTEST_PROP(MethodsPolygonClipProperty, HomogeneousMatchesTwoDimensionalForUnitW, ()) {
  const Polygon2 subject = random_star(10, false);
  std::vector<m::Vec4> subject_clip;
  for (const Vec2& v : subject) subject_clip.push_back({v.x / 4, v.y / 4, 0.5, 1});
  Polygon2 scaled;
  for (const Vec2& v : subject) scaled.push_back({v.x / 4, v.y / 4});
  const m::ClipVolume volume = m::homogeneous_volume(m::ClipDepthRange::ZeroToOne);
  const std::vector<m::Vec4> out = m::clip_polygon_sutherland_hodgman(subject_clip, volume);
  Polygon2 projected;
  for (const m::Vec4& v : out) {
    RC_ASSERT(m::outcode(volume, v) == 0);
    projected.push_back({v.x / v.w, v.y / v.w});
  }
  const Polygon2 expected = m::clip_polygon_sutherland_hodgman(scaled, m::Rect2{-1, -1, 1, 1});
  RC_ASSERT(std::fabs(m::signed_area(projected) - m::signed_area(expected)) < 1e-9);
}
