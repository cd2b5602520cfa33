// The spec profile (cpu_raster/spec, docs/spec-profile.md) on scenes small enough to classify by
// hand: inside / on an edge / outside, shared-edge promotion, facing, depth against the clear
// value, scissor, multisample pixels, lines, and a deliberately wrong rasterization rejected.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cpu_raster/spec/spec_primitives.hpp"
#include "cpu_raster/spec/spec_profile.hpp"
#include "cpu_raster/spec/subpixel.hpp"
#include "cpu_raster/spec/triangle_coverage.hpp"
#include "model/errors.hpp"
#include "test_spec_support.hpp"

namespace rastercmp {
namespace {

using namespace spec_test;

// 'M' Must, '?' May, '.' MustNot, one char per pixel (sample 0).
std::vector<std::string> class_rows(const Scene& scene, const std::vector<CoverageClass>& classes) {
  std::vector<std::string> rows(scene.height, std::string(scene.width, '.'));
  for (uint32_t y = 0; y < scene.height; ++y)
    for (uint32_t x = 0; x < scene.width; ++x) {
      const CoverageClass c = classes[(size_t(y) * scene.width + x) * scene.samples];
      rows[y][x] = c == CoverageClass::Must ? 'M' : c == CoverageClass::May ? '?' : '.';
    }
  return rows;
}

std::vector<CoverageClass> classify(const Scene& scene, uint32_t bits = 8) {
  return spec_coverage_classes(scene, spec_options(bits));
}

size_t count(const std::vector<std::string>& rows, char c) {
  size_t n = 0;
  for (const std::string& row : rows) n += size_t(std::count(row.begin(), row.end(), c));
  return n;
}

// Triangle (2,2), (10,2), (2,10). Pixel centres (x+.5, y+.5) with x, y >= 2 are inside by half a
// pixel from the legs; the hypotenuse x + y = 12 runs through the centres with x + y = 11 (May);
// centres with x + y <= 10 are inside by 1/sqrt(2) px, those with x + y >= 12 outside by as much.
TEST(SpecProfile, SmallTriangleIsMustInsideMayOnTheEdgeMustNotOutside) {
  Scene scene = make_scene(16, 16);
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}));
  const std::vector<std::string> expected = {
      "................",  //
      "................",  //
      "..MMMMMMM?......",  //
      "..MMMMMM?.......",  //
      "..MMMMM?........",  //
      "..MMMM?.........",  //
      "..MMM?..........",  //
      "..MM?...........",  //
      "..M?............",  //
      "..?.............",  //
      "................",  //
      "................",  //
      "................",  //
      "................",  //
      "................",  //
      "................",  //
  };
  EXPECT_EQ(class_rows(scene, classify(scene)), expected);
}

// The same triangle with the winding reversed classifies the same (coverage ignores winding).
TEST(SpecProfile, WindingDoesNotChangeCoverage) {
  Scene a = make_scene(16, 16), b = make_scene(16, 16);
  a.draws.push_back(window_triangles(a, {{2, 2}, {10, 2}, {2, 10}}));
  b.draws.push_back(window_triangles(b, {{2, 2}, {2, 10}, {10, 2}}));
  EXPECT_EQ(classify(a), classify(b));
}

// A quad of two triangles whose outer edges lie on pixel borders (half a pixel from every centre):
// the diagonal x + y = 14 runs through centres, which are PARTIAL for both triangles but lie
// inside both triangles' other edges, so exactly one of them covers each: promoted to Must.
TEST(SpecProfile, QuadDiagonalIsPromotedAndHasNoMayPixels) {
  Scene scene = make_scene(16, 16);
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {12, 2}, {2, 12}, {12, 2}, {12, 12}, {2, 12}}));
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  EXPECT_EQ(count(rows, '?'), 0u);
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x)
      EXPECT_EQ(rows[y][x], (x >= 2 && x < 12 && y >= 2 && y < 12) ? 'M' : '.') << x << "," << y;
}

// Each triangle alone leaves the diagonal May: the promotion needs the friend.
TEST(SpecProfile, HalfAQuadKeepsItsDiagonalMay) {
  Scene scene = make_scene(16, 16);
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {12, 2}, {2, 12}}));
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  for (uint32_t x = 2; x <= 11; ++x) EXPECT_EQ(rows[13 - x][x], '?') << x;
}

// Outer edges through pixel centres (corners on half pixels): those centres are May; the diagonal
// x + y = 15 (centres with x + y = 14) is promoted except at the two corners it shares with them.
TEST(SpecProfile, QuadOuterEdgesThroughCentresAreMayDiagonalIsMust) {
  Scene scene = make_scene(16, 16);
  scene.draws.push_back(
      window_triangles(scene, {{2.5, 2.5}, {12.5, 2.5}, {2.5, 12.5}, {12.5, 2.5}, {12.5, 12.5}, {2.5, 12.5}}));
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  for (uint32_t x = 3; x <= 11; ++x) EXPECT_EQ(rows[14 - x][x], 'M') << "diagonal at x " << x;
  for (uint32_t k = 2; k <= 12; ++k) {
    EXPECT_EQ(rows[2][k], '?') << "top edge at x " << k;
    EXPECT_EQ(rows[12][k], '?') << "bottom edge at x " << k;
    EXPECT_EQ(rows[k][2], '?') << "left edge at y " << k;
    EXPECT_EQ(rows[k][12], '?') << "right edge at y " << k;
  }
  EXPECT_EQ(rows[7][7], 'M');
  EXPECT_EQ(rows[1][7], '.');
  EXPECT_EQ(rows[13][7], '.');
}

// Two triangles with a common edge but on the SAME side of it (overlapping) are no pair.
TEST(SpecProfile, OverlappingTrianglesOnOneSideAreNotPromoted) {
  Scene scene = make_scene(16, 16);
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {12, 2}, {2, 12}, {12, 2}, {2, 12}, {1, 1}}));
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  for (uint32_t x = 2; x <= 11; ++x) EXPECT_EQ(rows[13 - x][x], '?') << x;
}

TEST(SpecProfile, CulledFacesAreMustNotAndTheOthersUnchanged) {
  Scene scene = make_scene(16, 16);
  // (2,2), (10,2), (2,10): right then down is clockwise on screen, Vulkan a = -32 < 0, so
  // back-facing with front_face ccw.
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}));
  const std::vector<CoverageClass> drawn = classify(scene);
  scene.draws[0].state.cull_mode = CullMode::Front;
  EXPECT_EQ(classify(scene), drawn);
  scene.draws[0].state.cull_mode = CullMode::Back;
  EXPECT_EQ(count(class_rows(scene, classify(scene)), '.'), 256u);
  scene.draws[0].state.front_face = FrontFace::Clockwise;
  EXPECT_EQ(classify(scene), drawn);
}

TEST(SpecProfile, FacingIsCertainOnlyBeyondTheRoundingSlack) {
  using cpu::spec::snap_triangle;
  EXPECT_EQ(snap_triangle({glm::dvec2(2, 2), glm::dvec2(10, 2), glm::dvec2(2, 10)}, 8).area_sign, -1);
  EXPECT_EQ(snap_triangle({glm::dvec2(2, 2), glm::dvec2(2, 10), glm::dvec2(10, 2)}, 8).area_sign, 1);
  // 2a = 14 px * 0.004 px = 3670 units^2; moving the apex one unit in x or y changes it by ~3600.
  EXPECT_EQ(snap_triangle({glm::dvec2(1, 1), glm::dvec2(15, 15), glm::dvec2(1, 1.004)}, 8).area_sign, 0);
  RasterState state;
  EXPECT_EQ(cpu::spec::facing_gate(state, 0), cpu::spec::Gate::Certain);
  state.cull_mode = CullMode::Back;
  EXPECT_EQ(cpu::spec::facing_gate(state, 0), cpu::spec::Gate::Maybe);
  EXPECT_EQ(cpu::spec::facing_gate(state, -1), cpu::spec::Gate::Never);
  EXPECT_EQ(cpu::spec::facing_gate(state, 1), cpu::spec::Gate::Certain);
}

// Such a sliver, back-facing as given, may still be drawn (a device's rounding can flip it).
TEST(SpecProfile, AmbiguousFacingIsMayNotMustNot) {
  Scene scene = make_scene(16, 16);
  scene.draws.push_back(window_triangles(scene, {{1, 1}, {15, 15}, {1, 1.004}}));
  scene.draws[0].state.cull_mode = CullMode::Back;
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  EXPECT_EQ(count(rows, 'M'), 0u);
  EXPECT_GT(count(rows, '?'), 0u);
}

TEST(SpecProfile, DepthAgainstTheClearValueDecides) {
  Scene scene = make_scene(16, 16);
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}, 0.5f));
  const std::vector<std::string> drawn = class_rows(scene, classify(scene));
  RasterState& state = scene.draws[0].state;
  state.depth.compare_op = CompareOp::Greater;  // 0.5 > 1.0 never holds
  EXPECT_EQ(count(class_rows(scene, classify(scene)), '.'), 256u);
  state.depth.compare_op = CompareOp::Never;
  EXPECT_EQ(count(class_rows(scene, classify(scene)), '.'), 256u);
  state.depth.compare_op = CompareOp::Equal;  // 0.5 == 1.0 neither: nothing
  EXPECT_EQ(count(class_rows(scene, classify(scene)), '.'), 256u);
  scene.depth_clear = 0.5f;  // equal to the clear value: up to rounding, so possibly
  EXPECT_EQ(count(class_rows(scene, classify(scene)), 'M'), 0u);
  EXPECT_EQ(count(class_rows(scene, classify(scene)), '?'), count(drawn, 'M') + count(drawn, '?'));
  state.depth.test_enable = false;
  EXPECT_EQ(class_rows(scene, classify(scene)), drawn);
  scene.depth_format = DepthFormat::None;
  state.depth.test_enable = true;
  EXPECT_EQ(class_rows(scene, classify(scene)), drawn);
}

// z within the slack below the clear value: Less may fail after rounding.
TEST(SpecProfile, DepthNearTheClearValueIsOnlyMay) {
  Scene scene = make_scene(16, 16);
  scene.depth_format = DepthFormat::D16Unorm;
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}, 0.99999f));
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  EXPECT_EQ(count(rows, 'M'), 0u);
  EXPECT_EQ(count(rows, '?'), 28u + 8u);  // the Must and May pixels of the triangle above
}

// A large constant depth bias could push a fragment past the clear value.
TEST(SpecProfile, DepthBiasWidensTheDepthRange) {
  Scene scene = make_scene(16, 16);
  scene.depth_format = DepthFormat::D16Unorm;
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}, 0.9f));
  EXPECT_EQ(count(class_rows(scene, classify(scene)), 'M'), 28u);
  scene.draws[0].state.depth_bias = DepthBias{true, 5000.0f, 0.0f, 0.0f};  // up to 5000 * 2/65535 = 0.15
  EXPECT_EQ(count(class_rows(scene, classify(scene)), 'M'), 0u);
  scene.draws[0].state.depth_bias.clamp = 0.01f;  // clamped below 0.01: certain again
  EXPECT_EQ(count(class_rows(scene, classify(scene)), 'M'), 28u);
}

TEST(SpecProfile, OutsideTheScissorIsMustNot) {
  Scene scene = make_scene(16, 16);
  scene.scissor = Rect2D{4, 3, 3, 100};
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}));
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x)
      if (x < 4 || x > 6 || y < 3) {
        EXPECT_EQ(rows[y][x], '.') << x << "," << y;
      }
  EXPECT_EQ(rows[3][4], 'M');
  EXPECT_EQ(rows[6][5], '?');  // 5 + 6 = 11: on the hypotenuse
  scene.scissor = Rect2D{4, 3, 0, 5};
  EXPECT_EQ(count(class_rows(scene, classify(scene)), '.'), 256u);
}

// Multisample pixels are judged as a whole square: a pixel whose border an edge runs along is
// May, every sample of a pixel has the pixel's class.
TEST(SpecProfile, MultisamplePixelsAreJudgedAsWholeSquares) {
  Scene scene = make_scene(16, 16, 4);
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}));
  const std::vector<CoverageClass> classes = classify(scene);
  const std::vector<std::string> rows = class_rows(scene, classes);
  EXPECT_EQ(rows[4][4], 'M');  // square [4,5]^2 (+3 units): corner sums up to 10.02 < 12
  EXPECT_EQ(rows[4][5], 'M');  // [5,6] x [4,5]: up to 11.02
  EXPECT_EQ(rows[5][5], '?');  // [5,6]^2 reaches x + y = 12.02: a centre-sampled pixel (Must) is May here
  EXPECT_EQ(rows[5][2], '?');  // the leg x = 2 is the pixel's left border
  EXPECT_EQ(rows[6][6], '?');  // [6,7]^2 touches the hypotenuse at its corner (6, 6)
  EXPECT_EQ(rows[7][7], '.');  // [7,8]^2: corner sums from 13.98
  EXPECT_EQ(rows[0][0], '.');
  for (size_t p = 0; p < size_t(16 * 16); ++p)
    for (uint32_t s = 1; s < 4; ++s) ASSERT_EQ(classes[p * 4 + s], classes[p * 4]) << p;
}

TEST(SpecProfile, RectangularLineIsMustOnlyAPixelInside) {
  Scene scene = make_scene(32, 32);
  Draw line;
  line.topology = Topology::LineList;
  line.state.line_mode = LineMode::Rectangular;
  line.state.line_width = 4;
  line.positions_clip = {clip_from_window(4, 16, 0.5f, 32, 32), clip_from_window(28, 16, 0.5f, 32, 32)};
  scene.draws.push_back(line);
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  // Rectangle [4, 28] x [14, 18]: centres 1 px + box inside are Must (x 5..26, y 15..16), centres
  // within 1 px (+ box, + 2 px past the ends) of it May, the rest MustNot.
  EXPECT_EQ(rows[15][5], 'M');
  EXPECT_EQ(rows[16][26], 'M');
  EXPECT_EQ(rows[14][10], '?');
  EXPECT_EQ(rows[17][10], '?');
  EXPECT_EQ(rows[13][10], '?');
  EXPECT_EQ(rows[18][10], '?');
  EXPECT_EQ(rows[15][4], '?');
  EXPECT_EQ(rows[12][10], '.');
  EXPECT_EQ(rows[19][10], '.');
  EXPECT_EQ(rows[16][0], '.');
  EXPECT_EQ(rows[16][31], '.');
  EXPECT_EQ(count(rows, 'M'), 22u * 2u);
}

// Only the segment is clipped: a wide line's pixels past the viewport are the device's choice,
// and so is clipping the segment at all.
TEST(SpecProfile, WideLinesAreMustOnlyInsideTheViewport) {
  Scene scene = make_scene(32, 32);
  scene.viewport = Viewport{0, 0, 16, 32, 0, 1};
  Draw line;
  line.topology = Topology::LineList;
  line.state.line_mode = LineMode::Rectangular;
  line.state.line_width = 6;
  // Window (4, 4) to (28, 28) through the viewport [0, 16] x [0, 32]: clip x = x / 8 - 1.
  line.positions_clip = {glm::vec4(4.0f / 8 - 1, 4.0f / 16 - 1, 0.5f, 1),
                         glm::vec4(28.0f / 8 - 1, 28.0f / 16 - 1, 0.5f, 1)};
  scene.draws.push_back(line);
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  EXPECT_EQ(rows[10][10], 'M');
  EXPECT_EQ(rows[14][14], 'M');  // centre 1.5 px from the viewport's edge x = 16
  EXPECT_EQ(rows[15][15], '?');  // on the line, but within a pixel of that edge
  EXPECT_EQ(rows[17][17], '?');  // past the viewport: the rectangle around the clipped end reaches here
  // The segment "may be clipped": the whole line, cut only by the scissor, is May too (a guard band).
  EXPECT_EQ(rows[22][22], '?');
  EXPECT_EQ(rows[10][22], '.');  // off the line by more than half the width and the margin
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 15; x < 32; ++x) EXPECT_NE(rows[y][x], 'M') << x << "," << y;
}

// A vertex the spec says nothing about (NaN) leaves every pixel in the scissor possible.
TEST(SpecProfile, NonFiniteVerticesMakeEverythingInTheScissorMay) {
  Scene scene = make_scene(16, 16);
  scene.scissor = Rect2D{2, 2, 8, 8};
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}));
  scene.draws[0].positions_clip[1].x = std::nanf("");
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  EXPECT_EQ(count(rows, '?'), 64u);
  EXPECT_EQ(count(rows, '.'), 256u - 64u);
  scene.draws[0].state.cull_mode = CullMode::FrontAndBack;  // culled whatever its facing
  EXPECT_EQ(count(class_rows(scene, classify(scene)), '.'), 256u);
}

TEST(SpecProfile, ThinBresenhamLineIsNeverMust) {
  Scene scene = make_scene(32, 32);
  Draw line;
  line.topology = Topology::LineList;
  line.state.line_mode = LineMode::Bresenham;
  line.positions_clip = {clip_from_window(3, 5, 0.5f, 32, 32), clip_from_window(29, 20, 0.5f, 32, 32)};
  scene.draws.push_back(line);
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  EXPECT_EQ(count(rows, 'M'), 0u);
  EXPECT_GT(count(rows, '?'), 26u * 3u);
  EXPECT_EQ(rows[30][1], '.');
}

TEST(SpecProfile, RenderResultCarriesTheLavapipeEstimateAndTheClasses) {
  Scene scene = make_scene(16, 16);
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}));
  const RenderResult spec = render_spec_profile(scene, spec_options(6), render_cpu(scene, lavapipe_options()));
  const RenderResult exact = render_cpu(scene, lavapipe_options());
  EXPECT_EQ(spec.backend, "cpu");
  EXPECT_EQ(spec.device, "cpu spec profile (subPixelPrecisionBits 6)");
  EXPECT_EQ(spec.owner, exact.owner);
  EXPECT_EQ(spec.depth_raw, exact.depth_raw);
  EXPECT_EQ(spec.coverage_class, classify(scene, 6));
  EXPECT_EQ(render_cpu(scene, spec_options(6)).coverage_class, spec.coverage_class);  // the CPU renderer's dispatch
  const Violations v = judge(spec.coverage_class, exact);
  EXPECT_FALSE(v.any()) << describe(v);
}

// The lavapipe profile's render shifted by one pixel (to the right, then down) is rejected.
TEST(SpecProfile, ARasterizationShiftedByOnePixelIsRejected) {
  Scene scene = make_scene(32, 32);
  scene.draws.push_back(window_triangles(scene, {{3.3, 4.1}, {27.6, 9.8}, {11.2, 28.7}}));
  const RenderResult exact = render_cpu(scene, lavapipe_options());
  const std::vector<CoverageClass> classes = classify(scene);
  EXPECT_FALSE(judge(classes, exact).any()) << describe(judge(classes, exact));
  for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
    RenderResult shifted = exact;
    for (uint32_t y = 0; y < 32; ++y)
      for (uint32_t x = 0; x < 32; ++x) {
        const bool inside = x >= uint32_t(dx) && y >= uint32_t(dy);
        shifted.owner[shifted.index(x, y)] = inside ? exact.owner[exact.index(x - dx, y - dy)] : kOwnerBackground;
      }
    const Violations v = judge(classes, shifted);
    EXPECT_GT(v.must_missing, 0u) << dx << "," << dy;
    EXPECT_GT(v.must_not_covered, 0u) << dx << "," << dy;
  }
}

TEST(SpecProfile, CoarserGridsAreMoreTolerant) {
  Scene scene = make_scene(32, 32);
  scene.draws.push_back(window_triangles(scene, {{3.3, 4.1}, {27.6, 9.8}, {11.2, 28.7}}));
  const std::vector<std::string> fine = class_rows(scene, classify(scene, 8));
  const std::vector<std::string> coarse = class_rows(scene, classify(scene, 2));
  EXPECT_GT(count(coarse, '?'), count(fine, '?'));
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 0; x < 32; ++x)
      if (coarse[y][x] != '?') {
        EXPECT_EQ(coarse[y][x], fine[y][x]) << x << "," << y;
      }
}

// One raw step of the format up (+1) or down (-1), for depths in [0, 1].
uint32_t step_raw(uint32_t raw, int direction) { return direction > 0 ? raw + 1 : raw - 1; }

RenderResult spec_render(const Scene& scene) {
  return render_spec_profile(scene, spec_options(), render_cpu(scene, lavapipe_options()));
}

// A sloped triangle: lavapipe's depth is inside every Must and May sample's interval, the bounds
// themselves are inside and one step past either is outside; inside the triangle vertex snapping
// sets the bounds, and the clear value is only in the intervals of pixels that may stay clear.
TEST(SpecProfile, DepthIntervalsHoldLavapipeAndRejectOneStepPastABound) {
  for (const DepthFormat format : {DepthFormat::D16Unorm, DepthFormat::X8D24Unorm, DepthFormat::D32Sfloat}) {
    Scene scene = make_scene(16, 16);
    scene.depth_format = format;
    Draw draw = window_triangles(scene, {{2, 2}, {14, 2}, {2, 14}}, 0.25f);
    draw.positions_clip[1].z = 0.75f;
    scene.draws.push_back(draw);
    const RenderResult spec = spec_render(scene);
    const RenderResult exact = render_cpu(scene, lavapipe_options());
    ASSERT_EQ(spec.depth_interval.size(), exact.depth_raw.size());
    EXPECT_FALSE(judge(spec, exact).any()) << describe(judge(spec, exact));
    const size_t i = exact.index(4, 4);
    ASSERT_EQ(spec.coverage_class[i], CoverageClass::Must);
    const DepthInterval d = spec.depth_interval[i];
    EXPECT_FALSE(d.any);
    EXPECT_EQ(d.lo_term, DepthTerm::Snapping);
    EXPECT_EQ(d.hi_term, DepthTerm::Snapping);
    const uint32_t clear = exact.depth_raw[exact.index(15, 15)];
    EXPECT_FALSE(depth_in_interval(format, d, clear));
    for (const uint32_t inside : {d.lo_raw, d.hi_raw}) {
      RenderResult moved = exact;
      moved.depth_raw[i] = inside;
      EXPECT_EQ(judge(spec, moved).depth_outside, 0u) << to_string(format);
    }
    for (const uint32_t outside : {step_raw(d.lo_raw, -1), step_raw(d.hi_raw, +1)}) {
      RenderResult moved = exact;
      moved.depth_raw[i] = outside;
      EXPECT_EQ(judge(spec, moved).depth_outside, 1u) << to_string(format);
    }
    // A pixel on the hypotenuse may keep the clear value.
    const size_t edge = exact.index(7, 8);  // centre (7.5, 8.5) on x + y = 16
    ASSERT_EQ(spec.coverage_class[edge], CoverageClass::May);
    EXPECT_TRUE(depth_in_interval(format, spec.depth_interval[edge], clear));
  }
}

// A flat triangle: only precision and rounding widen the interval, a few LSB of D16.
TEST(SpecProfile, FlatTriangleIntervalIsNarrow) {
  Scene scene = make_scene(16, 16);
  scene.depth_format = DepthFormat::D16Unorm;
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {14, 2}, {2, 14}}, 0.5f));
  const RenderResult spec = spec_render(scene);
  const DepthInterval d = spec.depth_interval[spec.index(4, 4)];
  EXPECT_LE(d.hi_raw - d.lo_raw, 12u);
  EXPECT_LE(d.lo_raw, 32768u);
  EXPECT_GE(d.hi_raw, 32767u);
}

// Depth bias moves the interval by r x constantFactor for every r the spec allows: at least
// 2^-16 each for D16; without depth clamp a bias that can leave [0, 1] makes the depth undefined
// (any value), with depth clamp it is clamped to the viewport's range.
TEST(SpecProfile, DepthBiasShiftsTheIntervalAndCanMakeItUndefined) {
  Scene scene = make_scene(16, 16);
  scene.depth_format = DepthFormat::D16Unorm;
  Draw draw = window_triangles(scene, {{2, 2}, {14, 2}, {2, 14}}, 0.5f);
  draw.state.depth_bias = DepthBias{true, 1000.0f, 0.0f, 0.0f};
  draw.state.depth.compare_op = CompareOp::Always;  // written whatever the clear value
  scene.draws.push_back(draw);
  const RenderResult spec = spec_render(scene);
  const DepthInterval d = spec.depth_interval[spec.index(4, 4)];
  EXPECT_GE(d.lo_raw, uint32_t(0.5 * 65535 + 1000 * 65535.0 / 65536) - 8);
  EXPECT_LE(d.hi_raw, uint32_t(0.5 * 65535 + 2000) + 8);
  EXPECT_EQ(d.hi_term, DepthTerm::Bias);
  EXPECT_FALSE(judge(spec, render_cpu(scene, lavapipe_options())).any());

  scene.draws[0].state.depth_bias.constant_factor = 40000.0f;  // up to 0.5 + 1.22
  const DepthInterval undefined = spec_render(scene).depth_interval[spec.index(4, 4)];
  EXPECT_TRUE(undefined.any);
  EXPECT_EQ(undefined.hi_term, DepthTerm::Undefined);
  scene.draws[0].state.depth_clamp = true;
  const RenderResult clamped = spec_render(scene);
  const DepthInterval c = clamped.depth_interval[clamped.index(4, 4)];
  EXPECT_FALSE(c.any);
  EXPECT_EQ(c.hi_raw, 65535u);
  EXPECT_FALSE(judge(clamped, render_cpu(scene, lavapipe_options())).any());
}

// docs/spec-profile.md "Lavapipe deviations", depth extrapolated past the vertices. lavapipe's depth
// plane runs through the float window vertices, its coverage through the snapped ones; a sample
// covered only after snapping gets a depth outside the vertices' range, which the profile rejects
// and the property tests accept as that deviation (accept_float_plane_extrapolation). Both scenes
// are tests/test_spec_properties.cpp failures, reduced to the primitive that wrote the sample.
struct ExtrapolatedSample {
  uint32_t x, y, sample, lavapipe_raw, lo_raw;
  DepthTerm lo_term;
};

void expect_extrapolation_deviation(const Scene& scene, const ExtrapolatedSample& e) {
  const RenderResult exact = render_cpu(scene, lavapipe_options());
  RenderResult spec = spec_render(scene);
  const size_t i = exact.index(e.x, e.y, e.sample);
  EXPECT_NE(exact.owner[i], kOwnerBackground);
  EXPECT_EQ(exact.depth_raw[i], e.lavapipe_raw);
  EXPECT_EQ(spec.depth_interval[i].lo_raw, e.lo_raw);
  EXPECT_EQ(spec.depth_interval[i].lo_term, e.lo_term);
  const Violations before = judge(spec, exact);
  EXPECT_EQ(before.depth_outside, 1u) << describe(before);
  EXPECT_EQ(accept_float_plane_extrapolation(scene, 8, spec, exact), 1u);
  EXPECT_TRUE(depth_in_interval(exact.depth_format, spec.depth_interval[i], exact.depth_raw[i]));
  const Violations after = judge(spec, exact);
  EXPECT_FALSE(after.any()) << describe(after);
}

// A clipped at the far plane (z_f = 0.375, reversed depth range 0.625..0.375, depth clip on):
// the piece's vertex (2.5, 2.49930096) snaps to (2.5, 2.5), the pixel centre; lavapipe's plane
// there is 0.375 - 0.3289 x 0.00070 = 0.374770 (raw 24560.6 -> 24561), below every vertex depth by
// more than the precision allowance (lo 0.374802 -> raw 24562).
TEST(SpecProfile, LavapipeDepthExtrapolatedPastAClippedFarPlaneIsTheKnownDeviation) {
  Scene scene = make_scene(10, 27);
  scene.depth_format = DepthFormat::D16Unorm;
  scene.viewport = Viewport{2.5f, 3, 4, -4, 0.625f, 0.375f};
  Draw draw;
  draw.state.depth.compare_op = CompareOp::Less;
  draw.positions_clip = {{4.2773438f, -1.1894531f, 0.53f, 1},
                         {-4.1796875f, -0.21741152f, 0.58000004f, 1},
                         {0.13476562f, -2, 3.94f, 1}};
  scene.draws.push_back(draw);
  expect_extrapolation_deviation(scene, {2, 2, 0, 24561, 24562, DepthTerm::Precision});
}

// B: 4x, a vertex behind the eye (w = -1.25), depth bias (-40, 0.25, clamp 1/64) clamped to
// 0.015625. Sample 1 of pixel (2, 2), at (2.875, 2.375), lies 0.00116 px outside the float piece's
// edge from (2.868, 0) to (2.888, 5.936), where z = 0, and inside the snapped one; lavapipe's plane
// there is -0.00055, plus the bias 0.015078 (raw 988), while the vertices' range plus the bias
// less the precision allowance is 0.015305 (raw 1003).
TEST(SpecProfile, LavapipeDepthExtrapolatedPastAClippedEdgeWithBiasIsTheKnownDeviation) {
  Scene scene = make_scene(4, 21, 4);
  scene.depth_format = DepthFormat::D16Unorm;
  Draw draw;
  draw.state.depth.compare_op = CompareOp::LessOrEqual;
  draw.state.depth_bias = DepthBias{true, -40.0f, 0.25f, 0.015625f};
  draw.positions_clip = {{1.3085938f, 0.065476194f, 0.81f, 1},
                         {-0.9147072f, -1.080073f, -0.3125f, -1.25f},
                         {0.49023438f, -0.22690637f, 0.04f, 1}};
  scene.draws.push_back(draw);
  expect_extrapolation_deviation(scene, {2, 2, 1, 988, 1003, DepthTerm::Bias});
}

// Inside the float triangle nothing is accepted: the sloped triangle of
// DepthIntervalsHoldLavapipeAndRejectOneStepPastABound with a stored depth moved past its bound.
TEST(SpecProfile, DepthPastTheIntervalInsideTheFloatTriangleIsNotAcceptedAsExtrapolation) {
  Scene scene = make_scene(16, 16);
  scene.depth_format = DepthFormat::D16Unorm;
  Draw draw = window_triangles(scene, {{2, 2}, {14, 2}, {2, 14}}, 0.25f);
  draw.positions_clip[1].z = 0.75f;
  scene.draws.push_back(draw);
  RenderResult spec = spec_render(scene);
  RenderResult moved = render_cpu(scene, lavapipe_options());
  const size_t i = moved.index(4, 4);
  moved.depth_raw[i] = spec.depth_interval[i].lo_raw - 1;
  EXPECT_EQ(accept_float_plane_extrapolation(scene, 8, spec, moved), 0u);
  EXPECT_EQ(judge(spec, moved).depth_outside, 1u);
}

// test_spec_properties found it (1 run in 900): without depth clipping the triangle crosses
// w_c = 0, and all three vertices have x_c / w_c = 1.6, so its plane holds the clip-space origin:
// the exact clipped polygon is the single point x_c = y_c = w_c = 0, which has no window position
// and no area. lavapipe's float clipper returns noise there (clip positions of size 1e-7, one
// w_c = -2.9e-12), a piece at window (6.5, -7), (6.5, 1.002), (-61526.6, -7) that reaches past the
// viewport's right side x = -1. The profile called its pixels (0..5, 0) Must; lavapipe covers
// nothing (its draw region ends at the viewport). No piece with a clipper-made vertex at w_c <= 0
// and no box outside the viewport rectangle is Must now.
Scene behind_eye_edge_on_scene(const Viewport& viewport) {
  Scene scene = make_scene(9, 19);
  scene.viewport = viewport;
  Draw draw;
  draw.state.depth_clamp = true;
  draw.state.depth_clip = false;
  draw.positions_clip = {{1.6f, 0.25f, 1.64f, 1}, {-2.4f, -0.5625f, -2.46f, -1.5f}, {1.6f, 0.3755474f, 1.64f, 1}};
  draw.indices = {0, 2, 1};
  scene.draws.push_back(draw);
  return scene;
}

TEST(SpecProfile, PieceOfAClippedPolygonDegenerateAtTheOriginIsNeverMust) {
  // The viewport (x -16..-1, y -7..1) lies left of the framebuffer.
  const Scene scene = behind_eye_edge_on_scene(Viewport{-16, -7, 15, 8, 0.625f, 0});
  const cpu::spec::SpecPrimitives primitives = cpu::spec::build_spec_primitives(scene, true, 8);
  ASSERT_EQ(primitives.triangles.size(), 1u);
  EXPECT_FALSE(primitives.triangles[0].shape_certain);
  const std::vector<std::string> rows = class_rows(scene, classify(scene));
  EXPECT_EQ(rows[0], "???????..");
  EXPECT_EQ(count(rows, 'M'), 0u);
  EXPECT_EQ(count(rows, '?'), 7u);
  const Violations v = judge(spec_render(scene), render_cpu(scene, lavapipe_options()));
  EXPECT_FALSE(v.any()) << describe(v);

  // Over the framebuffer (x 0..15, y 0..8) the same noise piece spans the viewport, and lavapipe
  // covers all 9 x 8 pixels there; a device clipping exactly covers none: May, not Must.
  const Scene inside = behind_eye_edge_on_scene(Viewport{0, 0, 15, 8, 0.625f, 0});
  const std::vector<std::string> inside_rows = class_rows(inside, classify(inside));
  EXPECT_EQ(count(inside_rows, 'M'), 0u);
  EXPECT_EQ(count(inside_rows, '?'), 72u);
  const Violations w = judge(spec_render(inside), render_cpu(inside, lavapipe_options()));
  EXPECT_FALSE(w.any()) << describe(w);
}

TEST(SpecProfile, NotSupportedAndBadOptions) {
  Scene scene = make_scene(16, 16);
  scene.draws.push_back(window_triangles(scene, {{2, 2}, {10, 2}, {2, 10}}));
  scene.draws[0].state.polygon_mode = PolygonMode::Line;
  EXPECT_THROW(classify(scene), NotSupportedError);
  scene.draws[0].state.polygon_mode = PolygonMode::Fill;
  scene.draws[0].topology = Topology::PointList;
  EXPECT_THROW(classify(scene), NotSupportedError);
  scene.draws[0].topology = Topology::TriangleList;
  EXPECT_THROW(classify(scene, 0), UsageError);
  EXPECT_EQ(cpu::spec::effective_sub_pixel_bits(20), 16u);
  scene.draws[0].indices = {0, 1, 7};
  EXPECT_THROW(classify(scene), InputError);
}

}  // namespace
}  // namespace rastercmp
