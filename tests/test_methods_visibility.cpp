// Visibility methods: back-face culling, the painter's algorithm, the BSP tree, and the z-buffer
// they are judged against.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "cpu_raster/methods/cull_back_face.hpp"
#include "cpu_raster/methods/visibility_bsp.hpp"
#include "cpu_raster/methods/visibility_painter.hpp"
#include "cpu_raster/methods/visibility_raster.hpp"

namespace m = rastercmp::methods;
using m::Polygon3;
using m::Vec3;
using m::Vec4;

namespace {

// The viewer of the view space: looking along +z from z = -infinity.
constexpr Vec4 kViewerAtMinusZ{0, 0, -1, 0};

int count_differences(const m::OwnerImage& a, const m::OwnerImage& b) {
  int differences = 0;
  for (size_t i = 0; i < a.owner.size(); ++i) differences += a.owner[i] != b.owner[i];
  return differences;
}

// The notes' "cyclic overlap" (lecture-rasterization-depth-sorting-culling.txt "Hard Cases"):
// three tilted sticks, A over B, B over C, C over A. A: horizontal band, nearer to the right;
// B: vertical band, nearer to the bottom; C: diagonal band, nearer to the top.
std::vector<Polygon3> cyclic_sticks() {
  auto z_a = [](double x, double) { return 10 - 0.3 * x; };
  auto z_b = [](double, double y) { return 10 - 0.3 * y; };
  auto z_c = [](double, double y) { return 1 + 0.2 * y; };
  auto quad = [](std::initializer_list<std::pair<double, double>> xy, auto z, uint32_t id) {
    Polygon3 p;
    p.id = id;
    for (const auto& [x, y] : xy) p.vertices.push_back({x, y, z(x, y)});
    return p;
  };
  return {quad({{0, 2}, {30, 2}, {30, 8}, {0, 8}}, z_a, 0), quad({{22, 0}, {28, 0}, {28, 30}, {22, 30}}, z_b, 1),
          quad({{5.5, -1.3}, {31.5, 28.7}, {28.5, 31.3}, {2.5, 1.3}}, z_c, 2)};
}

std::vector<Polygon3> in_order(const std::vector<Polygon3>& polygons, const std::vector<size_t>& order) {
  std::vector<Polygon3> out;
  for (size_t i : order) out.push_back(polygons[i]);
  return out;
}

rc::Gen<double> coordinate(double lo, double hi) {
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange<int64_t>(0, int64_t(1) << 20)),
                      [=](int64_t k) { return lo + (hi - lo) * double(k) / double(int64_t(1) << 20); });
}

}  // namespace

// The unit cube's faces with outward normals. From a corner direction three faces show; looking
// straight down one axis, one face shows and the four side faces are edge-on: hidden under the
// notes' "N.V <= 0", kept under the Cornell slides' "cull if N.V > 0" (V reversed).
TEST(MethodsVisibility, BackFaceCullingOfACube) {
  const Vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  auto visible = [&](Vec4 viewer, m::EdgeOnFace edge_on) {
    int count = 0;
    for (const Vec3& n : normals) count += !m::is_back_face(n, n, viewer, edge_on);
    return count;
  };
  EXPECT_EQ(visible({5, 4, 3, 1}, m::EdgeOnFace::Cull), 3);
  EXPECT_EQ(visible({1, 1, 1, 0}, m::EdgeOnFace::Cull), 3);
  EXPECT_EQ(visible({0, 0, 1, 0}, m::EdgeOnFace::Cull), 1);
  EXPECT_EQ(visible({0, 0, 1, 0}, m::EdgeOnFace::Keep), 5);
  EXPECT_EQ(visible({0, 0, 5, 1}, m::EdgeOnFace::Cull), 1);  // a near eye sees the side faces from behind
  // notes-line-clipping-hidden-surface.txt: with V = (0, 0, 1), remove the surface if c <= 0.
  for (const Vec3& n : normals) {
    EXPECT_EQ(m::is_back_face_view_along_z(n.z), m::is_back_face(n, {0, 0, 0}, {0, 0, 1, 0})) << n.x << n.y << n.z;
  }
}

// lecture-graphics-pipeline-cyrus-beck.txt "Painter's Algorithm": surfaces at z = 22, 18, 10 are
// drawn farthest first; for polygons parallel to the screen that is what a z-buffer shows.
TEST(MethodsVisibility, PainterMatchesZBufferForScreenParallelPolygons) {
  auto square = [](double x, double y, double z, uint32_t id) {
    return Polygon3{{{x, y, z}, {x + 12, y, z}, {x + 12, y + 12, z}, {x, y + 12, z}}, id};
  };
  const std::vector<Polygon3> scene{square(2, 2, 10, 0), square(6, 6, 22, 1), square(10, 3, 18, 2)};
  const std::vector<size_t> order = m::painter_order(scene);
  EXPECT_EQ(order, (std::vector<size_t>{1, 2, 0}));
  EXPECT_EQ(m::painter_order(scene, m::PainterKey::Centroid), order);
  const m::OwnerImage painted = m::paint_in_order(in_order(scene, order), 32, 32);
  const m::OwnerImage reference = m::paint_with_zbuffer(scene, 32, 32);
  EXPECT_EQ(count_differences(painted, reference), 0);
  EXPECT_EQ(reference.at(7, 7), 0u);    // z = 10 over z = 22
  EXPECT_EQ(reference.at(16, 10), 2u);  // z = 18 over z = 22
  EXPECT_EQ(reference.at(16, 16), 1u);  // only the farthest
  EXPECT_EQ(reference.at(0, 0), m::kNoOwner);
}

// Pinned: the cyclic triple. Every painter's order is wrong somewhere; the BSP tree splits the
// sticks and its back-to-front order paints exactly the z-buffer's image.
TEST(MethodsVisibility, BspPaintsCyclicOverlapWherePainterFails) {
  const std::vector<Polygon3> sticks = cyclic_sticks();
  const m::OwnerImage reference = m::paint_with_zbuffer(sticks, 32, 32);
  // The cycle is really there: each stick is in front of the next one somewhere.
  EXPECT_EQ(reference.at(25, 5), 0u);   // A over B
  EXPECT_EQ(reference.at(25, 25), 1u);  // B over C
  EXPECT_EQ(reference.at(8, 4), 2u);    // C over A
  for (m::PainterKey key : {m::PainterKey::FarthestVertex, m::PainterKey::Centroid}) {
    const m::OwnerImage painted = m::paint_in_order(in_order(sticks, m::painter_order(sticks, key)), 32, 32);
    EXPECT_GT(count_differences(painted, reference), 0);
  }
  const m::BspTree tree = m::build_bsp(sticks);
  EXPECT_GT(tree.splits, 0u);
  const m::OwnerImage bsp = m::paint_in_order(m::bsp_back_to_front(tree, kViewerAtMinusZ), 32, 32);
  EXPECT_EQ(count_differences(bsp, reference), 0);
  // Seen from the other side (z = +infinity) the BSP order matches a z-buffer keeping the larger z.
  std::vector<Polygon3> mirrored = sticks;
  for (Polygon3& p : mirrored) {
    for (Vec3& v : p.vertices) v.z = -v.z;
  }
  const m::OwnerImage from_behind = m::paint_in_order(m::bsp_back_to_front(tree, {0, 0, 1, 0}), 32, 32);
  EXPECT_EQ(count_differences(from_behind, m::paint_with_zbuffer(mirrored, 32, 32)), 0);
}

// RitaBSP with an eye point: two parallel squares swap their order when the eye crosses them.
TEST(MethodsVisibility, BspOrderFollowsTheEye) {
  const Polygon3 near_square{{{0, 0, 1}, {4, 0, 1}, {4, 4, 1}, {0, 4, 1}}, 7};
  const Polygon3 far_square{{{0, 0, 5}, {4, 0, 5}, {4, 4, 5}, {0, 4, 5}}, 8};
  const m::BspTree tree = m::build_bsp({near_square, far_square});
  EXPECT_EQ(tree.splits, 0u);
  const std::vector<Polygon3> from_front = m::bsp_back_to_front(tree, {2, 2, -10, 1});
  ASSERT_EQ(from_front.size(), 2u);
  EXPECT_EQ(from_front[0].id, 8u);
  const std::vector<Polygon3> from_back = m::bsp_back_to_front(tree, {2, 2, 20, 1});
  EXPECT_EQ(from_back[0].id, 7u);
  const std::vector<Polygon3> from_between = m::bsp_back_to_front(tree, {2, 2, 3, 1});
  EXPECT_EQ(from_between.size(), 2u);
  // A polygon without area is dropped; coplanar polygons share a node.
  const Polygon3 sliver{{{0, 0, 2}, {1, 1, 2}, {2, 2, 2}}, 9};
  const Polygon3 beside{{{5, 0, 1}, {6, 0, 1}, {6, 1, 1}}, 10};
  const m::BspTree tree2 = m::build_bsp({near_square, sliver, beside});
  ASSERT_EQ(tree2.nodes.size(), 1u);
  EXPECT_EQ(tree2.nodes[0].polygons.size(), 2u);
}

// Random triangles, interpenetrating freely: the BSP order paints what the z-buffer shows. A
// pixel may differ only where the two owners' depths tie to rounding (sample on an intersection line).
RC_GTEST_PROP(MethodsVisibilityProperty, BspMatchesZBuffer, ()) {
  const size_t n = *rc::gen::resize(100, rc::gen::inRange<size_t>(2, 7));
  std::vector<Polygon3> triangles;
  for (uint32_t id = 0; id < n; ++id) {
    Polygon3 t{{}, id};
    for (int k = 0; k < 3; ++k) t.vertices.push_back({*coordinate(-4, 28), *coordinate(-4, 28), *coordinate(0, 10)});
    const Vec3 normal = m::newell_normal(t.vertices);
    RC_PRE(std::fabs(normal.z) > 1);  // not nearly edge-on
    triangles.push_back(t);
  }
  const m::OwnerImage reference = m::paint_with_zbuffer(triangles, 24, 24);
  const m::BspTree tree = m::build_bsp(triangles);
  const m::OwnerImage bsp = m::paint_in_order(m::bsp_back_to_front(tree, kViewerAtMinusZ), 24, 24);
  RC_TAG(tree.splits > 0 ? "split" : "no split");
  for (int32_t y = 0; y < 24; ++y) {
    for (int32_t x = 0; x < 24; ++x) {
      const uint32_t want = reference.at(x, y), got = bsp.at(x, y);
      if (want == got) continue;
      RC_ASSERT(want != m::kNoOwner && got != m::kNoOwner);
      const m::Plane3 pw = m::plane_of(triangles[want]), pg = m::plane_of(triangles[got]);
      auto depth = [&](const m::Plane3& p) {
        return -(p.normal.x * (x + 0.5) + p.normal.y * (y + 0.5) + p.d) / p.normal.z;
      };
      RC_ASSERT(std::fabs(depth(pw) - depth(pg)) < 1e-9);
    }
  }
}

// Splitting keeps every piece on its side of the plane, and the pieces' area adds up.
RC_GTEST_PROP(MethodsVisibilityProperty, SplitPartitionsThePolygon, ()) {
  Polygon3 triangle{{}, 3};
  for (int k = 0; k < 3; ++k) triangle.vertices.push_back({*coordinate(-5, 5), *coordinate(-5, 5), *coordinate(-5, 5)});
  const Vec3 n{*coordinate(-1, 1), *coordinate(-1, 1), *coordinate(-1, 1)};
  RC_PRE(m::dot(n, n) > 1e-2);
  const m::Plane3 plane{n, *coordinate(-2, 2)};
  const m::SplitPolygon pieces = m::split(triangle, plane, 1e-12);
  auto area = [](const Polygon3& p) {
    const Vec3 a = m::newell_normal(p.vertices);
    return std::sqrt(m::dot(a, a)) / 2;
  };
  const double scale = std::sqrt(m::dot(n, n));
  for (const Vec3& v : pieces.front.vertices) RC_ASSERT(m::signed_distance(plane, v) / scale >= -1e-9);
  for (const Vec3& v : pieces.back.vertices) RC_ASSERT(m::signed_distance(plane, v) / scale <= 1e-9);
  RC_ASSERT(std::fabs(area(pieces.front) + area(pieces.back) - area(triangle)) < 1e-9);
  RC_ASSERT(pieces.front.id == 3u);
}
