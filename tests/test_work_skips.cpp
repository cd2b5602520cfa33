// The exact path's work skips (cpu_raster/work_skips.hpp) change nothing but the work done:
//  - 32-bit edge values equal the 64-bit ones over the largest boxes allowed, at negative
//    coordinates, with the top-left +1, at the overflow bound; boxes and planes past it keep 64 bits;
//  - the clipper hands a triangle or line wholly inside back unchanged, also where a plane distance
//    is not finite (where do_clip_tri would discard what lavapipe never clips);
//  - bias terms formed with zero factors leave the offset at exactly 0;
//  - every differential scene family and the skip scenes of bench/skip_scenes.hpp render to the same
//    owner and depth bytes with each skip on and off, and match lavapipe (0 differences).
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/skip_scenes.hpp"
#include "cpu_raster/exact/clip_line.hpp"
#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/clip_triangle.hpp"
#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/edge_frame32.hpp"
#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "model/host.hpp"
#include "tests/test_differential_scenes.hpp"

namespace rastercmp {
namespace {

using cpu::EdgeFrame32;
using cpu::EdgePlane;
using cpu::FixedPoint;
using cpu::PixelRect;
using cpu::PlaneSet;

// --- 32-bit edge values ---------------------------------------------------------------------------

FixedPoint at(int64_t x_fixed, int64_t y_fixed) {
  return FixedPoint{cpu::Fixed24_8{int32_t(x_fixed)}, cpu::Fixed24_8{int32_t(y_fixed)}};
}

PlaneSet triangle_planes(FixedPoint a, FixedPoint b, FixedPoint c) {
  PlaneSet planes;
  const std::array<FixedPoint, 3> v{a, b, c};
  for (size_t i = 0; i < 3; ++i) planes.push(cpu::make_edge(v[i], v[(i + 1) % 3], cpu::TieBreak::TopLeft));
  return planes;
}

// Every sample position of the box (pixel corner and the four standard 4x positions): 32-bit value
// against 64-bit value, plane by plane. Returns the number of samples compared.
uint64_t expect_same_values(const PlaneSet& planes, const PixelRect& box) {
  const std::optional<EdgeFrame32> frame = cpu::make_edge_frame32(planes, box);
  EXPECT_TRUE(frame.has_value()) << "box refused";
  if (!frame) return 0;
  uint64_t compared = 0;
  for (int32_t py = box.y0; py <= box.y1; ++py) {
    for (int32_t px = box.x0; px <= box.x1; ++px) {
      for (uint32_t s = 0; s < 5; ++s) {
        const cpu::SamplePoint p =
            s == 0 ? cpu::sample_point(px, py, 0, false) : cpu::sample_point(px, py, s - 1, true);
        const int32_t dx = int32_t(p.x_fixed - frame->x0_fixed), dy = int32_t(p.y_fixed - frame->y0_fixed);
        for (uint32_t i = 0; i < planes.count; ++i) {
          const int64_t wide = cpu::edge_value(planes.plane[i], p.x_fixed, p.y_fixed);
          const int32_t narrow = cpu::edge_value32(*frame, i, dx, dy);
          if (wide != narrow) {
            ADD_FAILURE() << "plane " << i << " at (" << px << ", " << py << ") sample " << s << ": 64-bit " << wide
                          << ", 32-bit " << narrow;
            return compared;
          }
        }
        EXPECT_EQ(cpu::first_failing_plane32(*frame, dx, dy), cpu::first_failing_plane(planes, p.x_fixed, p.y_fixed));
        ++compared;
      }
    }
  }
  return compared;
}

TEST(Edges32, LargestBoxMatches64BitAtEverySample) {
  // A 64x64 px box far from the origin; vertex differences up to the 2^14 limit in both axes, and both
  // windings (the edges of one are inclusive where the other's are not).
  const PixelRect box{3000, 1700, 3063, 1763};
  const int64_t x0 = 3000 * 256, y0 = 1700 * 256, d = cpu::kEdges32MaxDelta;
  EXPECT_EQ(expect_same_values(triangle_planes(at(x0, y0), at(x0 + 37, y0 + d), at(x0 + d, y0 + d - 5)), box),
            64u * 64 * 5);
  expect_same_values(triangle_planes(at(x0, y0 + d), at(x0 + d, y0), at(x0 + 1, y0 + 3)), box);
  expect_same_values(triangle_planes(at(x0 + d, y0 + d), at(x0, y0 + d / 2), at(x0 + d, y0)), box);
}

TEST(Edges32, NegativeCoordinatesMatch) {
  const PixelRect box{-40, -17, 23, 10};  // crosses both axes
  expect_same_values(
      triangle_planes(at(-40 * 256 + 3, -17 * 256), at(23 * 256 + 255, 2 * 256 + 7), at(-3 * 256, 10 * 256 + 200)),
      box);
  expect_same_values(triangle_planes(at(-40 * 256, 10 * 256), at(-1, -1), at(0, 0)), box);
}

TEST(Edges32, TopLeftBiasIsKept) {
  // A vertical left edge through pixel corners x = 5 (inclusive: E = 1 on it) and the right edge of
  // the mirrored triangle (exclusive: E = 0 on it).
  const PlaneSet left = triangle_planes(at(5 * 256, 0), at(5 * 256, 20 * 256), at(15 * 256, 10 * 256));
  const PlaneSet right = triangle_planes(at(5 * 256, 20 * 256), at(5 * 256, 0), at(-5 * 256, 10 * 256));
  ASSERT_TRUE(left.plane[0].inclusive);
  ASSERT_FALSE(right.plane[0].inclusive);
  const PixelRect box{0, 0, 15, 20};
  const auto frame_left = cpu::make_edge_frame32(left, box), frame_right = cpu::make_edge_frame32(right, box);
  ASSERT_TRUE(frame_left && frame_right);
  for (int32_t py = 0; py < 20; ++py) {
    EXPECT_EQ(cpu::edge_value32(*frame_left, 0, 5 * 256, py * 256), 1);
    EXPECT_EQ(cpu::edge_value32(*frame_right, 0, 5 * 256, py * 256), 0);
  }
  expect_same_values(left, box);
  expect_same_values(right, box);
}

TEST(Edges32, WorstCaseAtTheOverflowBound) {
  // Synthetic planes at every limit at once: |dcdx| = |dcdy| = 2^14, |c0| = 2^30, largest offsets.
  // The 32-bit value must equal the 64-bit one (it reaches 2^30 + 2^29 - 2^15 in magnitude).
  const PixelRect box{-64, 100, -1, 163};
  const int64_t x0 = -64 * 256, y0 = 100 * 256, d = cpu::kEdges32MaxDelta, m = cpu::kEdges32MaxOffset;
  int64_t largest = 0;
  for (int64_t sx : {-1, 1})
    for (int64_t sy : {-1, 1})
      for (int64_t sc : {-1, 1}) {
        EdgePlane plane{0, sx * d, sy * d, false};
        plane.c = sc * cpu::kEdges32MaxC0 - cpu::edge_value(plane, x0, y0);  // so that c0 = ±2^30
        PlaneSet planes;
        planes.push(plane);
        const auto frame = cpu::make_edge_frame32(planes, box);
        ASSERT_TRUE(frame.has_value());
        EXPECT_EQ(frame->c0[0], sc * cpu::kEdges32MaxC0);
        for (int64_t dx : {int64_t(0), m})
          for (int64_t dy : {int64_t(0), m}) {
            const int64_t wide = cpu::edge_value(plane, x0 + dx, y0 + dy);
            EXPECT_EQ(cpu::edge_value32(*frame, 0, int32_t(dx), int32_t(dy)), wide);
            largest = std::max(largest, wide < 0 ? -wide : wide);
          }
      }
  EXPECT_EQ(largest, cpu::kEdges32MaxC0 + 2 * cpu::kEdges32MaxDelta * cpu::kEdges32MaxOffset);
  EXPECT_GT(largest, int64_t(1) << 30);
}

TEST(Edges32, BoxesAndPlanesPastTheLimitsKeep64Bits) {
  const PlaneSet small = triangle_planes(at(0, 0), at(100, 9000), at(9000, 50));
  EXPECT_TRUE(cpu::make_edge_frame32(small, PixelRect{0, 0, 63, 63}).has_value());
  EXPECT_FALSE(cpu::make_edge_frame32(small, PixelRect{0, 0, 64, 63}).has_value());   // 65 px wide
  EXPECT_FALSE(cpu::make_edge_frame32(small, PixelRect{0, -1, 63, 63}).has_value());  // 65 px high
  EXPECT_FALSE(cpu::make_edge_frame32(small, PixelRect{5, 5, 4, 9}).has_value());     // empty
  const int64_t d = cpu::kEdges32MaxDelta;
  EXPECT_TRUE(cpu::make_edge_frame32(triangle_planes(at(0, 0), at(0, d), at(d, 0)), PixelRect{0, 0, 63, 63}));
  EXPECT_FALSE(cpu::make_edge_frame32(triangle_planes(at(0, 0), at(0, d + 1), at(d, 0)), PixelRect{0, 0, 63, 63}));
  PlaneSet far_constant;  // a plane whose value at the origin is past 2^30
  far_constant.push(EdgePlane{cpu::kEdges32MaxC0 + 1, 1, 0, false});
  EXPECT_FALSE(cpu::make_edge_frame32(far_constant, PixelRect{0, 0, 3, 3}).has_value());
  far_constant.plane[0].c = cpu::kEdges32MaxC0;
  EXPECT_TRUE(cpu::make_edge_frame32(far_constant, PixelRect{0, 0, 3, 3}).has_value());
}

TEST(Edges32, RandomTrianglesWithScissorPlanesMatch) {
  differential::Random rng(5);
  uint64_t compared = 0;
  for (int n = 0; n < 300; ++n) {
    const int32_t bx = rng.integer(-300, 300), by = rng.integer(-300, 300);
    const int32_t w = rng.integer(1, 64), h = rng.integer(1, 64);
    const PixelRect box{bx, by, bx + w - 1, by + h - 1};
    // Vertices anywhere the deltas allow: within 62 px of the box origin, any sub-pixel position.
    std::array<FixedPoint, 3> v;
    for (FixedPoint& p : v)
      p = at(int64_t(bx) * 256 + rng.integer(-256, 62 * 256), int64_t(by) * 256 + rng.integer(-256, 62 * 256));
    PlaneSet planes = triangle_planes(v[0], v[1], v[2]);
    const PixelRect region{bx + rng.integer(0, w / 2), by + rng.integer(0, h / 2), bx + w - 1 - rng.integer(0, w / 2),
                           by + h - 1 - rng.integer(0, h / 2)};
    cpu::add_scissor_planes(box, region, rng.chance(0.5f), planes);
    compared += expect_same_values(planes, box);
    if (HasFailure()) return;
  }
  EXPECT_GT(compared, 100000u);
}

// --- clipping a primitive wholly inside ------------------------------------------------------------

const cpu::ViewportTransform kViewport = cpu::make_viewport_transform(Viewport{0, 0, 64, 64, 0, 1});

cpu::ClipVertex clip_vertex(glm::vec4 pos, bool depth_clip = true) {
  return cpu::make_clip_vertex(pos, kViewport, depth_clip, true);
}

bool same_bits(const cpu::ClipVertex& a, const cpu::ClipVertex& b) {
  return std::memcmp(&a.pos_clip, &b.pos_clip, sizeof a.pos_clip) == 0 &&
         std::memcmp(&a.window, &b.window, sizeof a.window) == 0 && a.clip_mask == b.clip_mask &&
         a.made_by_clipper == b.made_by_clipper;
}

void expect_unchanged(const std::array<cpu::ClipVertex, 3>& triangle, uint32_t planes) {
  const cpu::ClippedTriangles skipped = cpu::clip_triangle(triangle, kViewport);
  const cpu::ClippedTriangles forced = cpu::clip_triangle(triangle, kViewport, planes);
  EXPECT_EQ(forced.fate, cpu::ClipFate::Inside);
  ASSERT_EQ(forced.triangles.size(), 1u);
  ASSERT_EQ(skipped.triangles.size(), 1u);
  for (size_t k = 0; k < 3; ++k) EXPECT_TRUE(same_bits(forced.triangles[0][k], triangle[k])) << "vertex " << k;
}

TEST(ClipSkip, TriangleInsideComesBackUnchangedFromEveryPlane) {
  differential::Random rng(9);
  for (int n = 0; n < 2000; ++n) {
    std::array<cpu::ClipVertex, 3> t;
    for (cpu::ClipVertex& v : t) {
      const float w = rng.uniform(0.01f, 100.0f);
      // Many vertices exactly on a plane (distance 0) as well as strictly inside.
      const auto coordinate = [&] { return rng.chance(0.2f) ? (rng.chance(0.5f) ? w : -w) : rng.uniform(-1, 1) * w; };
      const float x = coordinate(), y = coordinate(), z = rng.chance(0.2f) ? w : rng.uniform(0, 1) * w;
      v = clip_vertex({x, y, z, w});
      ASSERT_EQ(v.clip_mask, 0u);
    }
    expect_unchanged(t, cpu::tested_clip_planes(true));
  }
}

TEST(ClipSkip, NonFiniteDistancesTheClipTestLetsThroughStillPassUnchanged) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  const float huge = 3e38f;
  // w = +Inf: inside every plane, but w - x = Inf, which makes do_clip_tri discard.
  const auto a = clip_vertex({0.5f, 0.25f, 0.5f, inf}), b = clip_vertex({0, 0, 0.5f, 1}),
             c = clip_vertex({0.5f, 0, 0.5f, 1});
  ASSERT_EQ(a.clip_mask | b.clip_mask | c.clip_mask, 0u);
  expect_unchanged({a, b, c}, cpu::tested_clip_planes(true));
  // x + w overflows to +Inf (the test computes the same sum, 0 > Inf is false).
  const auto d = clip_vertex({huge, 0, 0.5f, huge});
  ASSERT_EQ(d.clip_mask, 0u);
  expect_unchanged({d, b, c}, cpu::tested_clip_planes(true));
  // z NaN without depth clipping: no depth bits, but z * 0 makes every distance NaN.
  const auto e = clip_vertex({0.5f, 0.5f, nan, 1}, false), f = clip_vertex({0, 0, 0.5f, 1}, false),
             g = clip_vertex({0.5f, 0, 0.5f, 1}, false);
  ASSERT_EQ(e.clip_mask, 0u);
  expect_unchanged({e, f, g}, cpu::tested_clip_planes(false));
  // Without the fallback the clipper would drop them: what lavapipe never does to an inside triangle.
  EXPECT_EQ(cpu::clip_triangle({clip_vertex({2, 0, 0.5f, 1}), a, b}, kViewport).fate, cpu::ClipFate::Discarded);
}

TEST(ClipSkip, LineInsideComesBackUnchanged) {
  const float inf = std::numeric_limits<float>::infinity();
  for (const auto& [p, q] : {std::pair{glm::vec4{1, -1, 0, 1}, glm::vec4{0.25f, 0.5f, 1, 1}},
                             std::pair{glm::vec4{0.5f, 0.5f, 0.5f, inf}, glm::vec4{0, 0, 0, 2}}}) {
    const std::array<cpu::ClipVertex, 2> line{clip_vertex(p), clip_vertex(q)};
    const cpu::ClippedLine forced = cpu::clip_line(line, kViewport, cpu::tested_clip_planes(true));
    EXPECT_EQ(forced.fate, cpu::ClipFate::Inside);
    EXPECT_EQ(forced.t0, 0.0f);
    EXPECT_EQ(forced.t1, 0.0f);
    EXPECT_TRUE(same_bits(forced.line[0], line[0]));
    EXPECT_TRUE(same_bits(forced.line[1], line[1]));
  }
}

// --- bias terms with zero factors -----------------------------------------------------------------

TEST(BiasSkip, TermsFormedWithZeroFactorsLeaveTheOffsetAtZero) {
  const std::array<cpu::WindowVertex, 3> sloped{{{1, 1, 0.1f}, {30, 2, 0.7f}, {4, 25, 0.4f}}};
  const DepthBias disabled{false, 5.0f, 2.0f, 0.0f};  // factors set but the bias is off
  const cpu::DepthOffset skipped = cpu::triangle_depth_offset(sloped, disabled, DepthFormat::X8D24Unorm);
  const cpu::DepthOffset formed = cpu::triangle_depth_offset(sloped, disabled, DepthFormat::X8D24Unorm, false);
  EXPECT_EQ(skipped.m, 0.0f);  // nothing formed
  EXPECT_GT(formed.m, 0.0f);   // the slope term was formed
  EXPECT_FALSE(formed.computed);
  EXPECT_EQ(std::signbit(formed.offset), false);
  EXPECT_EQ(formed.offset, 0.0f);
  // A triangle with zero float area: m is Inf or NaN, m * 0 is NaN; the offset must stay 0.
  const std::array<cpu::WindowVertex, 3> flat{{{1, 1, 0.1f}, {2, 2, 0.7f}, {3, 3, 0.4f}}};
  const cpu::DepthOffset nan_terms =
      cpu::triangle_depth_offset(flat, DepthBias{true, 0, 0, 0}, DepthFormat::D32Sfloat, false);
  EXPECT_FALSE(std::isfinite(nan_terms.m));
  EXPECT_EQ(nan_terms.offset, 0.0f);
  EXPECT_FALSE(std::signbit(nan_terms.offset));
}

// --- whole renders, each skip on and off ----------------------------------------------------------

struct SkipConfig {
  const char* name;
  cpu::WorkSkips skips;
};

std::vector<SkipConfig> skip_configs() {
  std::vector<SkipConfig> configs{{"all skips on", {}}};
  configs.push_back({"clip_only_when_needed off", {}});
  configs.back().skips.clip_only_when_needed = false;
  configs.push_back({"depth_only_when_attached off", {}});
  configs.back().skips.depth_only_when_attached = false;
  configs.push_back({"bias_only_when_enabled off", {}});
  configs.back().skips.bias_only_when_enabled = false;
  configs.push_back({"edges32_when_box_fits off", {}});
  configs.back().skips.edges32_when_box_fits = false;
  configs.push_back({"all skips off", {false, false, false, false}});
  return configs;
}

std::string first_difference(const RenderResult& a, const RenderResult& b) {
  if (a.owner.size() != b.owner.size() || a.depth_raw.size() != b.depth_raw.size()) return "different sizes";
  for (size_t i = 0; i < a.owner.size(); ++i)
    if (a.owner[i] != b.owner[i] || (!a.depth_raw.empty() && a.depth_raw[i] != b.depth_raw[i]))
      return fmt::format(
          "sample index {} (x {}, y {}): owner {} / {}{}", i, i / a.samples % a.width, i / a.samples / a.width,
          differential::describe_owner(a.owner[i]), differential::describe_owner(b.owner[i]),
          a.depth_raw.empty() ? "" : fmt::format(", depth {:#x} / {:#x}", a.depth_raw[i], b.depth_raw[i]));
  return "";
}

bool vulkan_available() {
  static const std::string reason = differential::missing_vulkan_reason();
  static const bool printed = [] {
    if (!reason.empty()) fmt::print("lavapipe comparison skipped: no Vulkan device: {}\n", reason);
    return true;
  }();
  (void)printed;
  return reason.empty();
}

// Renders `scene` with every configuration; all must give the same bytes, and match lavapipe.
void expect_skips_change_nothing(const Scene& scene) {
  const bool vulkan = vulkan_available();
  CpuOptions options;
  options.fma = vulkan ? differential::shared_renderer().device().fma : lavapipe_fuses_on_this_host();
  if (vulkan) options.lavapipe = &test::release_of(differential::shared_renderer());
  std::vector<RenderResult> results;
  for (const SkipConfig& config : skip_configs()) {
    options.skips = config.skips;
    results.push_back(render_cpu(scene, options));
    EXPECT_TRUE(results.back().owner == results.front().owner && results.back().depth_raw == results.front().depth_raw)
        << scene.name << ", " << config.name
        << " against all skips on: " << first_difference(results.front(), results.back());
  }
  if (!vulkan) return;
  VulkanRenderer& renderer = differential::shared_renderer();
  const RenderResult vk = renderer.render(scene);
  EXPECT_TRUE(renderer.validation_messages().empty());
  std::string report;
  const differential::DiffFigures f = differential::diff_results(scene, results.front(), vk, report);
  EXPECT_GT(f.covered_samples, 0u) << scene.name << " covers nothing";
  EXPECT_EQ(f.coverage_mismatches, 0u) << scene.name << " against lavapipe:\n" << report;
  EXPECT_EQ(f.depth_mismatches, 0u) << scene.name << " against lavapipe:\n" << report;
}

using SceneMaker = Scene (*)(uint32_t seed);
struct Family {
  const char* name;
  SceneMaker make;
};
void PrintTo(const Family& family, std::ostream* os) { *os << family.name; }

Scene rectangular_lines(uint32_t seed) { return differential::line_scene(seed, LineMode::Default); }
Scene bresenham_lines(uint32_t seed) { return differential::line_scene(seed, LineMode::Bresenham); }
Scene msaa_lines(uint32_t seed) { return differential::line_scene(seed, LineMode::Rectangular, 4); }
Scene grid(uint32_t seed) { return differential::grid_triangles(seed); }

// The scene families of tests/test_differential.cpp, two seeds each.
class SkipsOnDifferentialScenes : public ::testing::TestWithParam<std::tuple<Family, uint32_t>> {};

TEST_P(SkipsOnDifferentialScenes, SameBytesWithEachSkipOnAndOff) {
  const auto& [family, seed] = GetParam();
  expect_skips_change_nothing(family.make(seed));
}

const Family kFamilies[] = {
    {"grid", grid},
    {"perspective", differential::perspective_triangles},
    {"clipped", differential::clipped_triangles},
    {"sliver", differential::sliver_triangles},
    {"far", differential::far_triangles},
    {"bias_cull", differential::bias_cull_triangles},
    {"clamp_scissor", differential::clamp_scissor_triangles},
    {"multi", differential::multi_triangle_draws},
    {"rectangular_lines", rectangular_lines},
    {"bresenham_lines", bresenham_lines},
    {"centred_bresenham_lines", differential::centred_bresenham_lines},
    {"strips_fans", differential::strips_and_fans},
    {"msaa", differential::msaa_triangles},
    {"msaa_lines", msaa_lines},
    {"less", differential::less_triangles},
    {"msaa_less", differential::msaa_less_triangles},
    {"viewport", differential::viewport_triangles},
};

INSTANTIATE_TEST_SUITE_P(Families, SkipsOnDifferentialScenes,
                         ::testing::Combine(::testing::ValuesIn(kFamilies), ::testing::Values(1u, 2u)),
                         [](const auto& param_info) {
                           return std::string(std::get<0>(param_info.param).name) + "_seed" +
                                  std::to_string(std::get<1>(param_info.param));
                         });

// Scenes built so that each skip applies (or, for the controls, does not).
struct SkipScene {
  const char* name;
  skip_scenes::MeshSpec spec;
  uint32_t samples = 1;
  bool depth_test = true;
  std::optional<Rect2D> scissor = std::nullopt;
};

std::vector<SkipScene> skip_scene_list() {
  using skip_scenes::MeshSpec;
  return {
      {"inside", MeshSpec{128, 16}},                               // clip: nothing to clip
      {"crossing", MeshSpec{128, 16, 1.4f}},                       // clip: the border triangles
      {"depthless", MeshSpec{128, 16, 0.95f, DepthFormat::None}},  // depth: no attachment
      {"depthless_crossing", MeshSpec{128, 12, 1.3f, DepthFormat::None}},
      {"test_off", MeshSpec{128, 16, 0.95f, DepthFormat::D16Unorm}, 1, false},  // depth: attachment, test off
      {"bias_on", MeshSpec{128, 16, 0.95f, DepthFormat::D32Sfloat, true}},      // bias: applied
      {"bias_off", MeshSpec{128, 16, 0.95f, DepthFormat::D32Sfloat}},           // bias: off
      {"tiny_boxes", MeshSpec{128, 64}},                                        // edges32: 2 px cells
      {"boxes_at_the_limit", MeshSpec{256, 4, 0.95f, DepthFormat::X8D24Unorm, false, 3}},  // ~60 px cells
      {"huge_boxes", MeshSpec{1024, 2, 1.2f}},                                             // edges32: 64-bit only
      {"msaa", MeshSpec{128, 12, 1.2f, DepthFormat::X8D24Unorm, true}, 4},
      {"msaa_depthless", MeshSpec{128, 12, 0.95f, DepthFormat::None}, 4},
  };
}

Scene make_skip_scene(const SkipScene& s) {
  Scene scene = skip_scenes::grid_mesh(std::string("rastercmp.skips.") + s.name, s.spec);
  scene.samples = s.samples;
  scene.draws[0].state.depth.test_enable = s.depth_test;
  scene.scissor = s.scissor;
  return scene;
}

void PrintTo(const SkipScene& scene, std::ostream* os) { *os << scene.name; }

class SkipsOnSkipScenes : public ::testing::TestWithParam<SkipScene> {};

TEST_P(SkipsOnSkipScenes, SameBytesWithEachSkipOnAndOff) { expect_skips_change_nothing(make_skip_scene(GetParam())); }

INSTANTIATE_TEST_SUITE_P(Meshes, SkipsOnSkipScenes, ::testing::ValuesIn(skip_scene_list()),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

// Needles 2000 px long and 4 px wide at the far end, all with their apex on the first sample of a
// 48x48 scissor (in a 16384 px viewport over a 128x128 framebuffer): each visits at most 49x49 px,
// and every plane's value at the box origin is below 2^30, but the edges' coordinate differences
// reach 2^19, so their values inside the box exceed 2^31. Only the delta limit of edge_frame32.hpp
// keeps them at 64 bits.
Scene needles_through_a_small_scissor() {
  Scene scene = differential::make_scene("rastercmp.skips.needles", 128, 128, DepthFormat::X8D24Unorm);
  scene.viewport = Viewport{-8128, -8128, 16384, 16384, 0, 1};  // window = 64 + 8192 * ndc
  scene.scissor = Rect2D{40, 40, 48, 48};
  const auto clip = [](double wx, double wy, float z) {
    return glm::vec4{float((wx - 64.0) / 8192.0), float((wy - 64.0) / 8192.0), z, 1.0f};
  };
  Draw draw;
  draw.state = differential::always_state();
  const double apex = 40.5, length = 2000, width = 4, pi = 3.14159265358979;
  for (int k = 0; k < 64; ++k) {
    const double angle = (k + 0.5) / 64.0 * pi / 2;
    const double bx = apex + length * std::cos(angle), by = apex + length * std::sin(angle);
    draw.positions_clip.push_back(clip(apex, apex, 0.25f));
    draw.positions_clip.push_back(clip(bx, by, 0.75f));
    draw.positions_clip.push_back(clip(bx - width * std::sin(angle), by + width * std::cos(angle), 0.5f));
  }
  scene.draws.push_back(draw);
  return scene;
}

TEST(SkipsOnNeedles, SameBytesWithEachSkipOnAndOff) { expect_skips_change_nothing(needles_through_a_small_scissor()); }

// What the skip scenes exercise: counted on the exact front end, so that a scene meant to test a
// skip cannot silently stop doing so.
struct SceneCounts {
  uint32_t inside = 0, clipped = 0, rasterized = 0, boxes32 = 0, boxes64 = 0, with_depth_plane = 0;
};

SceneCounts count(const Scene& scene) {
  SceneCounts c;
  const cpu::FrameContext frame = cpu::make_frame_context(scene, true, {});
  cpu::run_front_end(frame, 0, [&](const cpu::PrimitiveOutcome& o) {
    c.inside += o.clip_fate == cpu::ClipFate::Inside;
    c.clipped += o.clip_fate == cpu::ClipFate::Clipped;
    if (!o.rasterized()) return;
    ++c.rasterized;
    c.with_depth_plane += o.raster.has_depth;
    if (cpu::make_edge_frame32(o.raster.planes, o.raster.visit))
      ++c.boxes32;
    else
      ++c.boxes64;
  });
  return c;
}

TEST(SkipScenes, EachSceneExercisesWhatItIsMeantTo) {
  std::vector<SkipScene> list = skip_scene_list();
  const auto find = [&](const std::string& name) {
    for (const SkipScene& s : list)
      if (name == s.name) return count(make_skip_scene(s));
    ADD_FAILURE() << name;
    return SceneCounts{};
  };
  const SceneCounts inside = find("inside"), crossing = find("crossing"), depthless = find("depthless");
  EXPECT_EQ(inside.clipped, 0u);
  EXPECT_EQ(inside.inside, 2u * 16 * 16);
  EXPECT_GT(crossing.clipped, 20u);
  EXPECT_GT(crossing.inside, 100u);
  EXPECT_EQ(depthless.with_depth_plane, 0u);
  EXPECT_EQ(find("test_off").with_depth_plane, 0u);
  EXPECT_EQ(find("bias_on").with_depth_plane, find("bias_on").rasterized);
  const SceneCounts tiny = find("tiny_boxes"), limit = find("boxes_at_the_limit"), huge = find("huge_boxes");
  EXPECT_EQ(tiny.boxes64, 0u);
  EXPECT_GT(limit.boxes32, 0u);
  EXPECT_GT(limit.boxes64, 0u);
  EXPECT_EQ(huge.boxes32, 0u);
  const SceneCounts needles = count(needles_through_a_small_scissor());
  EXPECT_EQ(needles.rasterized, 64u);
  EXPECT_EQ(needles.boxes32, 0u);
}

}  // namespace
}  // namespace rastercmp
