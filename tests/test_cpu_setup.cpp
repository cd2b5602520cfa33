// Triangle set-up, the draw region, scissor planes and binning (docs/lavapipe-rules.md §2.3-§2.6, §6,
// §7.5), with answers worked out by hand.
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <utility>

#include <gtest/gtest.h>

#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/binned_triangle.hpp"
#include "cpu_raster/exact/draw_region.hpp"
#include "cpu_raster/exact/pipeline_cull.hpp"
#include "cpu_raster/exact/triangle_setup.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu {
namespace {

struct SetupFixture {
  RasterState state;
  SetupContext context;
  SetupFixture() {
    context.framebuffer = PixelRect{0, 0, 15, 15};
    context.region = context.framebuffer;
    context.state = &state;
  }
  TriangleSetup run(std::array<WindowVertex, 3> v) const { return setup_triangle(v, 7, context); }
};

// Counter-clockwise on screen (y down): (1,1) -> (1,5) -> (5,1). Snapped with -0.5: X = 128, 128,
// 1152; Y = 128, 1152, 128. area = dx01*dy20 - dx20*dy01 = 0*0 - 1024*(-1024) > 0.
const std::array<WindowVertex, 3> kCcw = {WindowVertex{1, 1, 0}, WindowVertex{1, 5, 0}, WindowVertex{5, 1, 0}};
const std::array<WindowVertex, 3> kCw = {kCcw[0], kCcw[2], kCcw[1]};

TEST(CpuSetup, AreaSignGivesFacingAndClockwiseTrianglesAreSwapped) {
  SetupFixture f;
  const TriangleSetup ccw = f.run(kCcw);
  EXPECT_EQ(ccw.fate, SetupFate::Rasterized);
  EXPECT_EQ(ccw.area, 1024 * 1024);
  EXPECT_TRUE(ccw.front_facing);
  EXPECT_FALSE(ccw.swapped);
  const TriangleSetup cw = f.run(kCw);
  EXPECT_EQ(cw.area, -1024 * 1024);
  EXPECT_FALSE(cw.front_facing);
  EXPECT_TRUE(cw.swapped);  // (v0, v2, v1): the same fixed-point triangle as kCcw
  EXPECT_EQ(cw.raster.vertex_fixed[1].y.raw, ccw.raster.vertex_fixed[1].y.raw);
  EXPECT_EQ(cw.raster.owner, 7u);
}

TEST(CpuSetup, CullModesAndFrontFace) {
  SetupFixture f;
  f.state.cull_mode = CullMode::Back;
  EXPECT_EQ(f.run(kCcw).fate, SetupFate::Rasterized);
  EXPECT_EQ(f.run(kCw).fate, SetupFate::Culled);
  f.state.front_face = FrontFace::Clockwise;
  EXPECT_EQ(f.run(kCcw).fate, SetupFate::Culled);
  EXPECT_EQ(f.run(kCw).fate, SetupFate::Rasterized);
  f.state.cull_mode = CullMode::FrontAndBack;
  EXPECT_EQ(f.run(kCcw).fate, SetupFate::Culled);
}

// Collinear after snapping: (1,1), (3,3) and (2, 2 + 1/1024) snap to one line.
TEST(CpuSetup, ZeroFixedAreaIsAlwaysDropped) {
  SetupFixture f;
  const TriangleSetup t = f.run({WindowVertex{1, 1, 0}, WindowVertex{3, 3, 0}, WindowVertex{2, 2 + 1.0f / 1024, 0}});
  EXPECT_EQ(t.fate, SetupFate::Degenerate);
}

TEST(CpuSetup, EdgesOfTheSwappedTriangleCarryTheTopLeftBias) {
  SetupFixture f;
  const TriangleSetup t = f.run(kCcw);
  // Edges 0: (1,1)->(1,5) going down: left, inclusive. 1: (1,5)->(5,1) going up: right.
  // 2: (5,1)->(1,1) horizontal right to left: top, inclusive.
  EXPECT_TRUE(t.raster.planes.plane[0].inclusive);
  EXPECT_FALSE(t.raster.planes.plane[1].inclusive);
  EXPECT_TRUE(t.raster.planes.plane[2].inclusive);
  EXPECT_EQ(t.raster.planes.count, 3u);  // the box lies inside the region: no scissor planes
  // Bounding box: x0 = 128 >> 8 = 0, x1 = (1152 - 1) >> 8 = 4.
  EXPECT_EQ(t.bbox.x0, 0);
  EXPECT_EQ(t.bbox.x1, 4);
}

TEST(CpuSetup, BoxOutsideTheRegionIsDropped) {
  SetupFixture f;
  f.context.region = PixelRect{8, 8, 15, 15};
  EXPECT_EQ(f.run(kCcw).fate, SetupFate::OutsideRegion);
}

// lp_setup_set_viewports: x0 = 0.3 -> (int)(0.799) = 0; x1 = (int)(10.4 + 0.3 - 0.501) = 10.
// A flipped viewport (y = 8, height = -8) covers rows 0..7.
TEST(CpuRegion, ViewportPixelRectangleTruncatesAfterFloatAdds) {
  const PixelRect r = viewport_pixel_rect(make_viewport_transform(Viewport{0.3f, 0, 10.4f, 8, 0, 1}));
  EXPECT_EQ(r.x0, 0);
  EXPECT_EQ(r.x1, 10);
  EXPECT_EQ(r.y0, 0);
  EXPECT_EQ(r.y1, 7);
  const PixelRect flipped = viewport_pixel_rect(make_viewport_transform(Viewport{0, 8, 16, -8, 0, 1}));
  EXPECT_EQ(flipped.y0, 0);
  EXPECT_EQ(flipped.y1, 7);
  const PixelRect half = viewport_pixel_rect(make_viewport_transform(Viewport{2.5f, 0, 4, 4, 0, 1}));
  EXPECT_EQ(half.x0, 2);  // (int)(2.999)
  EXPECT_EQ(half.x1, 5);  // (int)(6.5 - 0.501)
}

TEST(CpuRegion, RegionIsFramebufferScissorAndViewport) {
  Scene scene;
  scene.width = 32;
  scene.height = 16;
  scene.scissor = Rect2D{4, 2, 100, 5};
  scene.viewport = Viewport{0, 0, 20, 16, 0, 1};
  const PixelRect r = draw_region(scene, make_viewport_transform(*scene.viewport));
  EXPECT_EQ(r.x0, 4);
  EXPECT_EQ(r.x1, 19);
  EXPECT_EQ(r.y0, 2);
  EXPECT_EQ(r.y1, 6);
}

// Left plane: E = Xs - 256*(x0 - 1) - adj; single sample exactly px >= x0; multisample (adj 127)
// also samples more than 127/256 into the column x0 - 1.
TEST(CpuRegion, ScissorPlanesAndTheMultisampleQuirk) {
  const PixelRect region{4, 4, 9, 9}, bbox{0, 0, 12, 12};
  PlaneSet single, multi;
  add_scissor_planes(bbox, region, false, single);
  add_scissor_planes(bbox, region, true, multi);
  ASSERT_EQ(single.count, 4u);
  const EdgePlane& left = single.plane[0];
  EXPECT_LE(edge_value(left, 3 * 256, 0), 0);
  EXPECT_GT(edge_value(left, 4 * 256, 0), 0);
  EXPECT_GT(edge_value(multi.plane[0], 3 * 256 + 160, 0), 0);  // sample 3 of column 3
  EXPECT_LE(edge_value(multi.plane[0], 3 * 256 + 96, 0), 0);   // sample 0 of column 3
  const EdgePlane& right = multi.plane[1];                     // right plane stays exact
  EXPECT_GT(edge_value(right, 9 * 256 + 224, 0), 0);
  EXPECT_LE(edge_value(right, 10 * 256 + 32, 0), 0);
  PlaneSet inside;
  add_scissor_planes(PixelRect{5, 5, 8, 8}, region, true, inside);
  EXPECT_EQ(inside.count, 0u);
}

// A box inside one 64x64 tile is rasterized over the whole tile; a larger one over the tiles of
// its part inside the region, so a region starting on a tile boundary is not left of it.
TEST(CpuRegion, BinnedAreaFollowsTiles) {
  const PixelRect region{64, 0, 127, 63};
  const PixelRect one = binned_area(PixelRect{70, 3, 80, 9}, region);
  EXPECT_EQ(one.x0, 64);
  EXPECT_EQ(one.x1, 127);
  const PixelRect many = binned_area(PixelRect{10, 3, 100, 9}, region);
  EXPECT_EQ(many.x0, 64);
  EXPECT_EQ(many.x1, 127);
  EXPECT_EQ(many.y0, 0);
  EXPECT_EQ(many.y1, 63);
}

// Two triangles cover an 8x8, 4-sample framebuffer with scissor (2,2) 4x4. Left/top planes let
// samples with an in-pixel offset above 127/256 through in column 1 and row 1: column 1 gets
// samples 1 and 3 (x 0.875, 0.625), row 1 samples 2 and 3 (y 0.625, 0.875), pixel (1,1) only
// sample 3. Right and bottom are exact.
TEST(CpuRegion, MultisampleScissorLeaksIntoTheColumnAndRowBefore) {
  Scene scene;
  scene.width = scene.height = 8;
  scene.samples = 4;
  scene.depth_format = DepthFormat::None;
  scene.scissor = Rect2D{2, 2, 4, 4};
  Draw draw;
  draw.positions_clip = {{-1, -1, 0.5f, 1}, {1, -1, 0.5f, 1}, {-1, 1, 0.5f, 1},
                         {1, -1, 0.5f, 1},  {1, 1, 0.5f, 1},  {-1, 1, 0.5f, 1}};
  scene.draws.push_back(draw);
  const RenderResult r = render_cpu(scene, CpuOptions{});
  const auto mask = [&](uint32_t x, uint32_t y) {
    uint32_t bits = 0;
    for (uint32_t s = 0; s < 4; ++s) bits |= (r.owner[r.index(x, y, s)] != kOwnerBackground) << s;
    return bits;
  };
  EXPECT_EQ(mask(1, 3), 0b1010u);
  EXPECT_EQ(mask(3, 1), 0b1100u);
  EXPECT_EQ(mask(1, 1), 0b1000u);
  EXPECT_EQ(mask(0, 3), 0u);
  EXPECT_EQ(mask(3, 3), 0b1111u);
  EXPECT_EQ(mask(5, 5), 0b1111u);
  EXPECT_EQ(mask(6, 3), 0u);
  EXPECT_EQ(mask(3, 6), 0u);
}

// draw_pipe_cull.c: det < 0 is counter-clockwise; zero counts as back-facing.
TEST(CpuPipelineCull, FloatDeterminantDecidesFacing) {
  const float det = pipeline_cull_determinant(kCcw);  // e = (-4, 0), f = (-4, 4): -16
  EXPECT_EQ(det, -16.0f);
  EXPECT_FALSE(pipeline_cull_drops(det, CullMode::Back, FrontFace::CounterClockwise));
  EXPECT_TRUE(pipeline_cull_drops(det, CullMode::Front, FrontFace::CounterClockwise));
  EXPECT_TRUE(pipeline_cull_drops(det, CullMode::Back, FrontFace::Clockwise));
  EXPECT_TRUE(pipeline_cull_drops(0.0f, CullMode::Back, FrontFace::CounterClockwise));
  EXPECT_FALSE(pipeline_cull_drops(0.0f, CullMode::Front, FrontFace::CounterClockwise));
}

// cvtps2dq: values outside int32, and NaN, become INT32_MIN.
TEST(CpuBinnedTriangle, SaturatingSnap) {
  EXPECT_EQ(snap_vertex_saturating(1000.5f, 0.5f, SnapRounding::NearestEven), 256000);
  EXPECT_EQ(snap_vertex_saturating(8388607.0f, 0.0f, SnapRounding::NearestEven), 2147483392);  // (2^23 - 1) * 256
  EXPECT_EQ(snap_vertex_saturating(8388608.0f, 0.0f, SnapRounding::NearestEven), INT32_MIN);   // 2^31
  EXPECT_EQ(snap_vertex_saturating(-8388608.0f, 0.0f, SnapRounding::NearestEven), INT32_MIN);  // -2^31 itself
  EXPECT_EQ(snap_vertex_saturating(std::nanf(""), 0.0f, SnapRounding::NearestEven), INT32_MIN);
}

TEST(CpuBinnedTriangle, DirectRangeEndsWhereShiftedEdgesCanWrap) {
  const auto tri = [](int32_t dx, int32_t dy) {
    return std::array<FixedPoint, 3>{FixedPoint{Fixed24_8{0}, Fixed24_8{0}}, FixedPoint{Fixed24_8{dx}, Fixed24_8{dy}},
                                     FixedPoint{Fixed24_8{0}, Fixed24_8{dy}}};
  };
  EXPECT_TRUE(in_direct_range(tri((1 << 22), (1 << 22) - 1)));  // |dcdx| + |dcdy| = 2^23 - 1
  EXPECT_FALSE(in_direct_range(tri((1 << 22), (1 << 22))));
}

// Inside the direct range llvmpipe's binned, tiled arithmetic gives exactly the plane test, 1x and
// 4x: random triangles in a 128x128 framebuffer (4 tiles), every pixel and sample compared.
TEST(CpuBinnedTriangle, MatchesThePlaneTestInsideTheDirectRange) {
  uint64_t state = 0x9E3779B97F4A7C15ull;
  const auto next = [&](int32_t bound) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return int32_t((state >> 33) % uint64_t(bound));
  };
  const PixelRect fb{0, 0, 127, 127};
  int compared = 0, covered = 0;
  for (int n = 0; n < 24; ++n) {
    std::array<FixedPoint, 3> v;
    for (FixedPoint& p : v) p = FixedPoint{Fixed24_8{next(128 * 256)}, Fixed24_8{next(128 * 256)}};
    if (wrapped_doubled_area(v) == 0) continue;
    if (wrapped_doubled_area(v) < 0) std::swap(v[1], v[2]);
    const PixelRect bbox = wrapped_triangle_bbox(v);
    std::array<LpPlane, 8> lp{};
    const std::array<LpPlane, 3> edges = lp_edge_planes(v);
    std::copy(edges.begin(), edges.end(), lp.begin());
    for (const bool ms : {false, true}) {
      const BinnedTriangle binned = bin_triangle(lp, 3, bbox, fb, fb, ms);
      for (int32_t py = 0; py < 128; ++py)
        for (int32_t px = 0; px < 128; ++px)
          for (uint32_t s = 0; s < (ms ? 4u : 1u); ++s) {
            const int64_t x = int64_t(px) * 256 + (ms ? kStandardSamples4x[s].x_fixed : 0);
            const int64_t y = int64_t(py) * 256 + (ms ? kStandardSamples4x[s].y_fixed : 0);
            bool in = true;
            for (size_t i = 0; i < 3; ++i)
              in = in && edge_value(make_edge(v[i], v[(i + 1) % 3], TieBreak::TopLeft), x, y) > 0;
            ASSERT_EQ(binned_covers(binned, px, py, s), in) << n << " " << px << "," << py << " s" << s;
            ++compared;
            covered += in;
          }
    }
  }
  EXPECT_GT(covered, compared / 20);
}

// The triangle the clipper makes of (1.1e12, 1.4e12), (-4e13, 2.29e13), (9.2e16, -3.18e17), w = 1,
// in a 16x16 framebuffer: window (0, 1048584), (0, 0), (8, 0), a quad half of its fan. Its long
// edges, 268437504 fixed units (0x10000800) high, wrap when shifted by 8 (0x00080000), and the
// binned arithmetic covers every pixel, x >= 8 included, as lavapipe does; the plane test (x < 8)
// would not. At 128x128 the same clipped vertex lies at y = 8388672: beyond 2^31 / 256, snapped to
// INT32_MIN, and nothing is covered (lavapipe draws nothing either).
TEST(CpuBinnedTriangle, HugeClippedTriangleWrapsAsLlvmpipe) {
  SetupFixture f;
  const TriangleSetup small = f.run({WindowVertex{0, 1048584, 0}, WindowVertex{0, 0, 0}, WindowVertex{8, 0, 0}});
  ASSERT_EQ(small.fate, SetupFate::Rasterized);
  ASSERT_TRUE(small.raster.binned);
  EXPECT_TRUE(small.swapped);
  const BinnedTriangle& t = *small.raster.binned;
  EXPECT_EQ(t.plane[0].dcdx, 0x00080000);  // (268437376 - -128) << 8, wrapped
  EXPECT_EQ(t.plane[2].dcdx, -0x00080000);
  int covered = 0;
  for (int32_t py = 0; py < 16; ++py)
    for (int32_t px = 0; px < 16; ++px) covered += binned_covers(t, px, py, 0);
  EXPECT_EQ(covered, 256);
  EXPECT_FALSE(small.raster.visit.empty());
  EXPECT_EQ(small.raster.visit.x1, 15);  // not limited to the vertices' extent (x <= 7)

  SetupFixture big;
  big.context.framebuffer = PixelRect{0, 0, 127, 127};
  big.context.region = big.context.framebuffer;
  const TriangleSetup huge = big.run({WindowVertex{0, 8388672, 0}, WindowVertex{0, 0, 0}, WindowVertex{64, 0, 0}});
  EXPECT_EQ(huge.raster.vertex_fixed[0].y.raw, INT32_MIN);
  int huge_covered = 0;
  if (huge.fate == SetupFate::Rasterized && huge.raster.binned)
    for (int32_t py = 0; py < 128; ++py)
      for (int32_t px = 0; px < 128; ++px) huge_covered += binned_covers(*huge.raster.binned, px, py, 0);
  EXPECT_EQ(huge_covered, 0);
}

}  // namespace
}  // namespace rastercmp::cpu
