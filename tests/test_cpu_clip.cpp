// Clipping (docs/lavapipe-rules.md §1.3, §1.5, §1.6) with answers worked out by hand on a 4x4 viewport
// (scale 2, translate 2 in x and y; depth 0..1).
#include <array>
#include <limits>

#include <gtest/gtest.h>

#include "cpu_raster/exact/clip_line.hpp"
#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/clip_triangle.hpp"
#include "cpu_raster/exact/float_ops.hpp"

namespace rastercmp::cpu {
namespace {

const ViewportTransform kViewport = make_viewport_transform(Viewport{0, 0, 4, 4, 0, 1});

ClipVertex vertex(float x, float y, float z = 0.5f, float w = 1, bool depth_clip = true) {
  return make_clip_vertex({x, y, z, w}, kViewport, depth_clip, true);
}

void expect_position(const ClipVertex& v, float x, float y) {
  EXPECT_EQ(v.pos_clip.x, x);
  EXPECT_EQ(v.pos_clip.y, y);
}

TEST(CpuClip, MaskUsesUnorderedComparesSoNaNIsOutside) {
  EXPECT_EQ(clip_mask({0, 0, 0.5f, 1}, true), 0u);
  EXPECT_EQ(clip_mask({2, 0, 0.5f, 1}, true), 1u << kClipRight);
  EXPECT_EQ(clip_mask({-2, 0, 0.5f, 1}, true), 1u << kClipLeft);
  EXPECT_EQ(clip_mask({0, 0, -0.5f, 1}, true), 1u << kClipNear);
  EXPECT_EQ(clip_mask({0, 0, -0.5f, 1}, false), 0u);  // depth clip off: no z bits
  EXPECT_EQ(clip_mask({0, 0, 2, 1}, true), 1u << kClipFar);
  EXPECT_EQ(clip_mask({1, 1, 1, 1}, true), 0u);  // on the planes is inside
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(clip_mask({nan, 0, 0.5f, 1}, true), (1u << kClipRight) | (1u << kClipLeft));
}

// (0,0) (2,0) (0,1) against x <= w: v1 is out. Going out from v0 (dp 1) to v1 (dp -1): equal
// distances, so the new vertex starts from v0: (1, 0). Coming back from v1 to v2 (dp 1): starts
// from v2: v2 + 0.5*(v1 - v2) = (1, 0.5). Polygon v0, (1,0), (1,0.5), v2; fan of two triangles.
TEST(CpuClip, TriangleCrossingOnePlaneBecomesAFanOfTwo) {
  const ClippedTriangles c = clip_triangle({vertex(0, 0), vertex(2, 0), vertex(0, 1)}, kViewport);
  EXPECT_EQ(c.fate, ClipFate::Clipped);
  ASSERT_EQ(c.triangles.size(), 2u);
  expect_position(c.triangles[0][0], 0, 0);
  expect_position(c.triangles[0][1], 1, 0);
  expect_position(c.triangles[0][2], 1, 0.5f);
  expect_position(c.triangles[1][1], 1, 0.5f);
  expect_position(c.triangles[1][2], 0, 1);
  EXPECT_FALSE(c.triangles[0][0].made_by_clipper);  // original: keeps its JIT window position
  EXPECT_TRUE(c.triangles[0][1].made_by_clipper);
  EXPECT_EQ(c.triangles[0][1].window.x, 4.0f);  // ((1*1)*2)+2
  EXPECT_EQ(c.triangles[0][2].window.y, 3.0f);
}

// The fan lives inside ClippedTriangles (ClippedFan): a copy, an assignment over a longer fan and
// a self-assignment keep exactly the triangles, in order.
TEST(CpuClip, ClippedTrianglesCopyTheirFan) {
  const ClippedTriangles two = clip_triangle({vertex(0, 0), vertex(2, 0), vertex(0, 1)}, kViewport);
  ClippedTriangles copy = two;
  ASSERT_EQ(copy.triangles.size(), 2u);
  expect_position(copy.triangles[1][1], 1, 0.5f);
  ClippedTriangles three = clip_triangle({vertex(0, 0), vertex(2, 0), vertex(0, 2)}, kViewport);
  ASSERT_EQ(three.triangles.size(), 3u);
  three = two;
  ASSERT_EQ(three.triangles.size(), 2u);
  expect_position(three.triangles[0][2], 1, 0.5f);
  const ClippedTriangles& same = three;
  three = same;
  ASSERT_EQ(three.triangles.size(), 2u);
  expect_position(three.triangles[1][2], 0, 1);
}

// (0,0) (2,0) (0,2): x <= w first gives v0, (1,0), (1,1), v2. Then y <= w: (1,1) lies on the
// plane (dp 0, kept), going out to v2 starts from (1,1) with t = 0 (a second new vertex at the
// same place), coming back in from v2 to v0 gives (0,1). Five vertices, three triangles, the
// middle one degenerate (set-up drops it for zero area).
TEST(CpuClip, TriangleCrossingTwoPlanesKeepsTheClippersDegenerateFan) {
  const ClippedTriangles c = clip_triangle({vertex(0, 0), vertex(2, 0), vertex(0, 2)}, kViewport);
  ASSERT_EQ(c.triangles.size(), 3u);
  expect_position(c.triangles[0][1], 1, 0);
  expect_position(c.triangles[0][2], 1, 1);
  expect_position(c.triangles[1][1], 1, 1);
  expect_position(c.triangles[1][2], 1, 1);
  EXPECT_TRUE(c.triangles[1][1].made_by_clipper);  // made by the first pass, kept by the second
  EXPECT_TRUE(c.triangles[1][2].made_by_clipper);  // made by the second pass at t = 0
  expect_position(c.triangles[2][2], 0, 1);
}

// docs/lavapipe-rules.md §7.10: do_clip_tri runs under FTZ/DAZ. (0.5,-0.5) (5e37,0) (0.5,0.5)
// against x <= w: going out from v0, dp = 0.5, denom = 0.5 - (1 - 5e37) = 5e37, t = 0.5/5e37 =
// 1e-38 is denormal and flushes to 0, so the new vertex is v0 itself (x 0.5, not 1); likewise on
// the way back in. Without the flush x = 0.5 + 1e-38*(5e37 - 0.5) = 1.
TEST(CpuClip, DenormalInterpolationParameterFlushesToZero) {
  const std::array<ClipVertex, 3> t = {vertex(0.5f, -0.5f), vertex(5e37f, 0), vertex(0.5f, 0.5f)};
  {
    const DenormalsFlushed ftz_daz;
    const ClippedTriangles flushed = clip_triangle(t, kViewport);
    ASSERT_EQ(flushed.fate, ClipFate::Clipped);
    ASSERT_EQ(flushed.triangles.size(), 2u);
    for (const auto& tri : flushed.triangles)
      for (const ClipVertex& v : tri) EXPECT_EQ(v.pos_clip.x, 0.5f);  // a zero-area fan
  }
  const DenormalsKept kept;
  const ClippedTriangles exact = clip_triangle(t, kViewport);
  ASSERT_EQ(exact.triangles.size(), 2u);
  EXPECT_EQ(exact.triangles[0][1].pos_clip.x, 1.0f);
}

TEST(CpuClip, TrivialAcceptAndReject) {
  const ClippedTriangles inside = clip_triangle({vertex(0, 0), vertex(0.5f, 0), vertex(0, 0.5f)}, kViewport);
  EXPECT_EQ(inside.fate, ClipFate::Inside);
  ASSERT_EQ(inside.triangles.size(), 1u);
  const ClippedTriangles outside = clip_triangle({vertex(2, 0), vertex(3, 0), vertex(2, 0.5f)}, kViewport);
  EXPECT_EQ(outside.fate, ClipFate::Outside);
  EXPECT_TRUE(outside.triangles.empty());
}

TEST(CpuClip, NonFinitePlaneDistanceDropsThePrimitive) {
  const float inf = std::numeric_limits<float>::infinity();
  const ClippedTriangles c = clip_triangle({vertex(0, 0), vertex(inf, 0), vertex(0, 0.5f)}, kViewport);
  EXPECT_EQ(c.fate, ClipFate::Discarded);
  EXPECT_TRUE(c.triangles.empty());
}

TEST(CpuClip, DepthClipOffKeepsGeometryBeyondTheDepthPlanes) {
  const ClippedTriangles c = clip_triangle(
      {vertex(0, 0, -3, 1, false), vertex(0.5f, 0, 3, 1, false), vertex(0, 0.5f, 0.5f, 1, false)}, kViewport);
  EXPECT_EQ(c.fate, ClipFate::Inside);
  const ClippedTriangles on = clip_triangle(
      {vertex(0, 0, -3, 1, true), vertex(0.5f, 0, 3, 1, true), vertex(0, 0.5f, 0.5f, 1, true)}, kViewport);
  EXPECT_EQ(on.fate, ClipFate::Clipped);
}

// (0,0) -> (2,0): x <= w gives dp0 = 1, dp1 = -1, t1 = -1/(-1-1) = 0.5, v1' = v1 + 0.5*(v0 - v1).
TEST(CpuClip, LineClipMovesTheOutsideEndpoint) {
  const ClippedLine c = clip_line({vertex(0, 0), vertex(2, 0)}, kViewport);
  EXPECT_EQ(c.fate, ClipFate::Clipped);
  expect_position(c.line[0], 0, 0);
  EXPECT_FALSE(c.line[0].made_by_clipper);
  expect_position(c.line[1], 1, 0);
  EXPECT_TRUE(c.line[1].made_by_clipper);
}

// (-2,5) -> (5,-2) passes beside the corner (1,1): the right plane gives t1 = 4/7, the bottom
// plane t0 = 4/7, and t0 + t1 >= 1 drops it though no single plane has both ends out.
TEST(CpuClip, LineOutsideBothPlanesIsDropped) {
  EXPECT_EQ(clip_line({vertex(-2, 5), vertex(5, -2)}, kViewport).fate, ClipFate::Outside);
  EXPECT_EQ(clip_line({vertex(-2, 3), vertex(3, -2)}, kViewport).fate, ClipFate::Clipped);  // crosses (0,1)-(1,0)
  EXPECT_EQ(clip_line({vertex(2, 0), vertex(3, 0)}, kViewport).fate, ClipFate::Outside);
}

}  // namespace
}  // namespace rastercmp::cpu
