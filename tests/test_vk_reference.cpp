// The Vulkan reference on lavapipe, against answers worked out by hand from the top-left rule
// and the depth conversions of docs/lavapipe-rules.md. Every render runs with the validation layer
// and must produce no message. Skips only when no Vulkan device exists.
#include <bit>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <glm/vec2.hpp>

#include "model/depth_format.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"
#include "tests/test_vulkan_support.hpp"
#include "vk_reference/vk_context.hpp"
#include "vk_reference/vk_gather.hpp"
#include "vk_reference/vk_reference.hpp"
#include "vk_reference/vk_translate.hpp"

namespace rastercmp {
namespace {

using test::missing_vulkan_reason;
using test::shared_renderer;

// Window (framebuffer) coordinates → clip position for the default viewport of a w x h scene.
// Exact for power-of-two sizes: 2*x/w - 1 and the driver's (w/2)*x_c + w/2 round nowhere.
glm::vec4 clip_from_window(float x, float y, float z, uint32_t w, uint32_t h) {
  return {2.0f * x / float(w) - 1.0f, 2.0f * y / float(h) - 1.0f, z, 1.0f};
}

Scene make_scene(uint32_t w, uint32_t h, DepthFormat depth_format = DepthFormat::D32Sfloat) {
  Scene scene;
  scene.name = "test.vk_reference";
  scene.width = w;
  scene.height = h;
  scene.depth_format = depth_format;
  return scene;
}

// A triangle list from window-space (x, y) vertices at depth z.
Draw window_triangles(const Scene& scene, const std::vector<glm::vec2>& xy, float z) {
  Draw draw;
  for (const glm::vec2& p : xy) draw.positions_clip.push_back(clip_from_window(p.x, p.y, z, scene.width, scene.height));
  return draw;
}

// The two triangles (0,0),(w,0),(0,h) and (w,0),(w,h),(0,h) covering the framebuffer.
Draw full_screen(const Scene& scene, float z) {
  const float w = float(scene.width), h = float(scene.height);
  return window_triangles(scene, {{0, 0}, {w, 0}, {0, h}, {w, 0}, {w, h}, {0, h}}, z);
}

class VkReferenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string reason = missing_vulkan_reason();
    if (!reason.empty()) GTEST_SKIP() << "no Vulkan device: " << reason;
  }

  RenderResult render(const Scene& scene) {
    VulkanRenderer& renderer = shared_renderer();
    RenderResult result = renderer.render(scene);
    expect_no_validation_messages();
    EXPECT_EQ(result.width, scene.width);
    EXPECT_EQ(result.height, scene.height);
    EXPECT_EQ(result.samples, scene.samples);
    EXPECT_EQ(result.owner.size(), size_t(scene.width) * scene.height * scene.samples);
    return result;
  }

  static void expect_no_validation_messages() {
    const std::vector<std::string>& messages = shared_renderer().validation_messages();
    for (const std::string& m : messages) ADD_FAILURE() << "validation: " << m;
    ASSERT_TRUE(messages.empty());
  }
};

// rows[y][x]: '.' background, a digit p: owner (draw, p).
void expect_owner_grid(const RenderResult& result, const std::vector<std::string>& rows, uint32_t draw) {
  ASSERT_EQ(rows.size(), result.height);
  int mismatches = 0;
  std::string first;
  for (uint32_t y = 0; y < result.height; ++y) {
    ASSERT_EQ(rows[y].size(), result.width);
    for (uint32_t x = 0; x < result.width; ++x) {
      const char c = rows[y][x];
      const uint32_t expected = c == '.' ? kOwnerBackground : encode_owner(draw, uint32_t(c - '0'));
      const uint32_t actual = result.owner[result.index(x, y)];
      if (actual != expected && mismatches++ == 0) {
        first = fmt::format("first at ({}, {}): expected {:#x}, got {:#x}", x, y, expected, actual);
      }
    }
  }
  EXPECT_EQ(mismatches, 0) << first;
}

TEST_F(VkReferenceTest, DeviceIsLavapipeWithHostFma) {
  const DeviceInfo& device = shared_renderer().device();
  EXPECT_TRUE(device.is_lavapipe);
  EXPECT_NE(device.name.find("llvmpipe"), std::string::npos);
  EXPECT_EQ(device.fma, lavapipe_fuses_on_this_host());
  EXPECT_EQ(device.sub_pixel_precision_bits, 8u);  // docs/lavapipe-rules.md §0
  Scene scene = make_scene(4, 4);
  scene.draws.push_back(full_screen(scene, 0.5f));
  const RenderResult result = render(scene);
  EXPECT_EQ(result.backend, "vulkan");
  EXPECT_NE(result.device.find("llvmpipe"), std::string::npos);
  EXPECT_EQ(result.fma, device.fma);
}

// The shared diagonal x + y = 8 belongs to exactly one triangle: it is the right/bottom edge of
// triangle 0 (exclusive) and the left edge of triangle 1 (inclusive), so centres with
// x + y = 7 (pixel indices) go to primitive 1 (docs/lavapipe-rules.md §2.4).
TEST_F(VkReferenceTest, FullScreenPairCoversEveryPixelOnceSplitByTopLeftRule) {
  Scene scene = make_scene(8, 8);
  scene.draws.push_back(full_screen(scene, 0.5f));
  const RenderResult result = render(scene);
  expect_owner_grid(result,
                    {"00000001",  //
                     "00000011",  //
                     "00000111",  //
                     "00001111",  //
                     "00011111",  //
                     "00111111",  //
                     "01111111",  //
                     "11111111"},
                    0);
}

// Vertices on pixel centres (2.5,0.5), (6.5,4.5), (2.5,6.5). Left edge x = 2.5 inclusive; the
// upper-right edge y = x - 2 and the lower edge are right/bottom edges, exclusive. So (2,0) and
// (2,6) (vertices) and the centres on the slanted edges, e.g. (3,1), (6,4), (4,5), are out.
TEST_F(VkReferenceTest, TriangleOnPixelCentresCoversTopLeftRuleSet) {
  Scene scene = make_scene(8, 8);
  scene.draws.push_back(window_triangles(scene, {{2.5f, 0.5f}, {6.5f, 4.5f}, {2.5f, 6.5f}}, 0.5f));
  const RenderResult result = render(scene);
  expect_owner_grid(result,
                    {"........",  //
                     "..0.....",  //
                     "..00....",  //
                     "..000...",  //
                     "..0000..",  //
                     "..00....",  //
                     "........",  //
                     "........"},
                    0);
}

struct DepthCase {
  DepthFormat format;
  uint32_t raw;
};

// z = 0.5 everywhere (constant plane). D16: fl(0.5*0.99998474) = 0.5 - 2^-17, + 128 rounds half
// to even to 128.5, low 16 bits 0x8000 (docs/lavapipe-rules.md §3.5). D24: rne(8388607.5) = 8388608.
// D32: the float 0.5.
TEST_F(VkReferenceTest, ConstantDepthStoresExpectedRawValueInEachFormat) {
  for (const DepthCase& c : {DepthCase{DepthFormat::D16Unorm, 0x8000u}, DepthCase{DepthFormat::X8D24Unorm, 8388608u},
                             DepthCase{DepthFormat::D32Sfloat, 0x3F000000u}}) {
    SCOPED_TRACE(to_string(c.format));
    Scene scene = make_scene(4, 4, c.format);
    scene.draws.push_back(full_screen(scene, 0.5f));
    const RenderResult result = render(scene);
    ASSERT_TRUE(result.has_depth());
    EXPECT_EQ(result.depth_format, c.format);
    for (size_t i = 0; i < result.depth_raw.size(); ++i) {
      ASSERT_EQ(result.depth_raw[i], c.raw) << "texel " << i;
      ASSERT_EQ(owner_draw(result.owner[i]), 0u);
    }
  }
}

// The depth clear is stored through the same conversion: 1.0 → all ones of each format.
TEST_F(VkReferenceTest, DepthClearReadsBackAsFormatMaximum) {
  for (const DepthCase& c : {DepthCase{DepthFormat::D16Unorm, 0xFFFFu}, DepthCase{DepthFormat::X8D24Unorm, 0xFFFFFFu},
                             DepthCase{DepthFormat::D32Sfloat, 0x3F800000u}}) {
    SCOPED_TRACE(to_string(c.format));
    Scene scene = make_scene(4, 4, c.format);
    scene.draws.push_back(window_triangles(scene, {{0, 0}, {1, 0}, {0, 1}}, 0.5f));
    const RenderResult result = render(scene);
    EXPECT_EQ(result.depth_raw[result.index(3, 3)], c.raw);
    EXPECT_EQ(result.owner[result.index(3, 3)], kOwnerBackground);
  }
}

// (0,0), (8,0), (0,8) has negative signed area in Vulkan's y-down framebuffer, so with the
// default front face (counter-clockwise) it is back-facing; with clockwise it is front-facing.
TEST_F(VkReferenceTest, BackFaceCulledTriangleCoversNothingAndClockwiseFrontFaceFlipsIt) {
  const std::vector<std::string> upper_left = {"0000000.", "000000..", "00000...", "0000....",
                                               "000.....", "00......", "0.......", "........"};
  Scene scene = make_scene(8, 8);
  Draw draw = window_triangles(scene, {{0, 0}, {8, 0}, {0, 8}}, 0.5f);
  draw.state.cull_mode = CullMode::Back;
  scene.draws = {draw};
  expect_owner_grid(render(scene), std::vector<std::string>(8, "........"), 0);

  scene.draws[0].state.front_face = FrontFace::Clockwise;
  expect_owner_grid(render(scene), upper_left, 0);

  scene.draws[0].state.cull_mode = CullMode::Front;
  expect_owner_grid(render(scene), std::vector<std::string>(8, "........"), 0);
}

// Draw 0 at z = 0.25, draw 1 at z = 0.75 fails LESS everywhere; draw 2 at z = 0.125 passes on its
// triangle. Owners name the draw in the top 8 bits.
TEST_F(VkReferenceTest, LaterDrawBehindFailsDepthLessAndCloserDrawOverwrites) {
  Scene scene = make_scene(8, 8, DepthFormat::D32Sfloat);
  scene.draws.push_back(full_screen(scene, 0.25f));
  scene.draws.push_back(full_screen(scene, 0.75f));
  scene.draws.push_back(window_triangles(scene, {{0, 0}, {0, 8}, {8, 0}}, 0.125f));
  const RenderResult result = render(scene);
  for (uint32_t y = 0; y < 8; ++y) {
    for (uint32_t x = 0; x < 8; ++x) {
      const bool in_front = x + y <= 6;  // same diagonal rule as the full-screen pair
      const uint32_t owner = result.owner[result.index(x, y)];
      const uint32_t depth = result.depth_raw[result.index(x, y)];
      EXPECT_EQ(owner_draw(owner), in_front ? 2u : 0u) << x << "," << y;
      EXPECT_EQ(depth, in_front ? 0x3E000000u : 0x3E800000u) << x << "," << y;  // 0.125f : 0.25f
    }
  }
}

TEST_F(VkReferenceTest, ScissorRestrictsCoverage) {
  Scene scene = make_scene(8, 8);
  scene.scissor = Rect2D{2, 1, 3, 4};  // pixels x 2..4, y 1..4
  scene.draws.push_back(full_screen(scene, 0.5f));
  const RenderResult result = render(scene);
  expect_owner_grid(result,
                    {"........",  //
                     "..000...",  //
                     "..000...",  //
                     "..001...",  //
                     "..011...",  //
                     "........",  //
                     "........",  //
                     "........"},
                    0);
}

// 4x4 framebuffer, 4 samples at the standard locations x = .375, .875, .125, .625 (docs/lavapipe-rules.md
// §6). Draw 0 covers everything; draw 1, in front, ends at the vertical edge x = 1.5, so pixel
// column 1 keeps draw 1 in samples 0 and 2 (x < .5) and draw 0 in samples 1 and 3. Both draws are
// single triangles reaching outside the viewport (clipped; the primitive id stays 0).
TEST_F(VkReferenceTest, Msaa4xHalfCoveredPixelHasExpectedSampleOwners) {
  Scene scene = make_scene(4, 4, DepthFormat::D32Sfloat);
  scene.samples = 4;
  scene.draws.push_back(window_triangles(scene, {{-4, -4}, {20, -4}, {-4, 20}}, 0.5f));
  scene.draws.push_back(window_triangles(scene, {{1.5f, -4}, {1.5f, 8}, {-6, 2}}, 0.25f));
  const RenderResult result = render(scene);
  ASSERT_TRUE(result.has_depth());  // every sample's depth, read back by the depth gather
  ASSERT_EQ(result.depth_raw.size(), result.owner.size());
  const uint32_t back = encode_owner(0, 0), front = encode_owner(1, 0);
  const uint32_t back_depth = 0x3F000000u, front_depth = 0x3E800000u;  // 0.5f and 0.25f
  for (uint32_t y = 0; y < 4; ++y) {
    for (uint32_t x = 0; x < 4; ++x) {
      const uint32_t expected[4] = {x <= 1 ? front : back, x == 0 ? front : back, x <= 1 ? front : back,
                                    x == 0 ? front : back};
      for (uint32_t s = 0; s < 4; ++s) {
        const size_t i = result.index(x, y, s);
        EXPECT_EQ(result.owner[i], expected[s]) << x << "," << y << " sample " << s;
        EXPECT_EQ(result.depth_raw[i], expected[s] == front ? front_depth : back_depth)
            << x << "," << y << " sample " << s;
      }
    }
  }
}

// Multisampled depth is read back per sample: the sampled float turns back into the stored raw
// bits. A depth clear of 0.75 and a draw at 0.5 over columns 1..3 (its left edge x = 1 passes no
// sample position, so whole pixels are in or out; column 0 keeps the clear): every sample of the 4x
// render must read back the raw bits the single-sample copy path reads for its pixel, per format.
TEST_F(VkReferenceTest, Msaa4xDepthReadsBackTheRawBitsOfEachSample) {
  for (const DepthFormat format : {DepthFormat::D16Unorm, DepthFormat::X8D24Unorm, DepthFormat::D32Sfloat}) {
    SCOPED_TRACE(to_string(format));
    Scene single = make_scene(4, 4, format);
    single.depth_clear = 0.75f;
    single.draws.push_back(window_triangles(single, {{1, 0}, {4, 0}, {1, 4}, {4, 0}, {4, 4}, {1, 4}}, 0.5f));
    const RenderResult one = render(single);
    Scene multi = single;
    multi.samples = 4;
    const RenderResult four = render(multi);
    ASSERT_TRUE(one.has_depth());
    ASSERT_TRUE(four.has_depth());
    for (uint32_t y = 0; y < 4; ++y) {
      for (uint32_t x = 0; x < 4; ++x) {
        for (uint32_t s = 0; s < 4; ++s) {
          EXPECT_EQ(four.depth_raw[four.index(x, y, s)], one.depth_raw[one.index(x, y)])
              << x << "," << y << " sample " << s;
        }
      }
    }
    EXPECT_NE(one.depth_raw[one.index(0, 0)], one.depth_raw[one.index(1, 0)]);
  }
}

// Each conversion a device may sample UNORM depth by is inverted exactly, every raw value of D16
// and X8_D24: the raw value comes back, except ReciprocalProduct's one collision (0xFFFFFE and
// 0xFFFFFF both sample as 1.0). The two conversions differ: Quotient's float read back as
// ReciprocalProduct's is one step low or no value's conversion for about a quarter of X8_D24 each
// (every 61st value tried), so
// the reference must know which one the device does.
TEST(VkUnormSampling, EachConversionInvertsExactly) {
  for (const DepthFormat format : {DepthFormat::D16Unorm, DepthFormat::X8D24Unorm}) {
    SCOPED_TRACE(to_string(format));
    const uint32_t max = depth_format_info(format).raw_mask;
    for (const vk::UnormSampling sampling : vk::kUnormSamplings) {
      SCOPED_TRACE(vk::to_string(sampling));
      uint32_t wrong = 0, first_wrong = 0;
      for (uint32_t raw = 0; raw <= max; ++raw) {
        const uint32_t bits = std::bit_cast<uint32_t>(vk::sampled_unorm(sampling, raw, max));
        if (vk::depth_raw_from_sampled(format, sampling, bits) != raw && wrong++ == 0) first_wrong = raw;
      }
      const bool collides = sampling == vk::UnormSampling::ReciprocalProduct && format == DepthFormat::X8D24Unorm;
      EXPECT_EQ(wrong, collides ? 1u : 0u);
      if (collides) {
        EXPECT_EQ(first_wrong, 0xFFFFFEu);
      }
    }
  }
  uint32_t low = 0, unmatched = 0, tried = 0;
  for (uint32_t raw = 0; raw <= 0xFFFFFFu; raw += 61, ++tried) {
    const uint32_t bits = std::bit_cast<uint32_t>(vk::sampled_unorm(vk::UnormSampling::Quotient, raw, 0xFFFFFF));
    try {
      if (vk::depth_raw_from_sampled(DepthFormat::X8D24Unorm, vk::UnormSampling::ReciprocalProduct, bits) != raw) ++low;
    } catch (const std::runtime_error&) {
      ++unmatched;
    }
  }
  EXPECT_GT(low, tried / 5);
  EXPECT_GT(unmatched, tried / 5);
  EXPECT_THROW(
      vk::depth_raw_from_sampled(DepthFormat::D16Unorm, vk::UnormSampling::Quotient, std::bit_cast<uint32_t>(1.5f)),
      std::runtime_error);
}

// lavapipe samples both UNORM depth formats as llvmpipe's one float multiply (measured on the
// device, shaders/sample_depth.comp); D32 needs no conversion.
TEST_F(VkReferenceTest, LavapipeSamplesUnormDepthAsOneFloatMultiply) {
  const vk::Context context(VkOptions{"", /*validate=*/true});
  EXPECT_EQ(vk::measure_unorm_sampling(context, DepthFormat::D16Unorm), vk::UnormSampling::ReciprocalProduct);
  EXPECT_EQ(vk::measure_unorm_sampling(context, DepthFormat::X8D24Unorm), vk::UnormSampling::ReciprocalProduct);
  EXPECT_EQ(vk::measure_unorm_sampling(context, DepthFormat::D32Sfloat), std::nullopt);
  for (const std::string& m : context.validation_messages()) ADD_FAILURE() << "validation: " << m;
}

// A width-1 line along y = 3.5 from x = 0 to 8 is the rectangle 3 <= y <= 4 (rectangular lines,
// strictLines): exactly the centres of row 3.
TEST_F(VkReferenceTest, LineListDrawsTheExpectedRow) {
  Scene scene = make_scene(8, 8);
  Draw line = window_triangles(scene, {{0, 3.5f}, {8, 3.5f}}, 0.5f);
  line.topology = Topology::LineList;
  scene.draws.push_back(line);
  const RenderResult result = render(scene);
  std::vector<std::string> rows(8, "........");
  rows[3] = "00000000";
  expect_owner_grid(result, rows, 0);
}

// Bresenham (diamond exit) gives the same row: every centre on the segment is a diamond it crosses,
// and the end point (8, 3.5) lies outside the framebuffer (docs/lavapipe-rules.md §5.1, §5.4).
TEST_F(VkReferenceTest, BresenhamLineModeDrawsTheSameRow) {
  Scene scene = make_scene(8, 8);
  Draw line = window_triangles(scene, {{0, 3.5f}, {8, 3.5f}}, 0.5f);
  line.topology = Topology::LineList;
  line.state.line_mode = LineMode::Bresenham;
  scene.draws.push_back(line);
  std::vector<std::string> rows(8, "........");
  rows[3] = "00000000";
  expect_owner_grid(render(scene), rows, 0);
}

// Width 3: the rectangle 2 <= y <= 5 holds the centres of rows 2, 3 and 4.
TEST_F(VkReferenceTest, WideLineCoversThreeRows) {
  Scene scene = make_scene(8, 8);
  Draw line = window_triangles(scene, {{0, 3.5f}, {8, 3.5f}}, 0.5f);
  line.topology = Topology::LineStrip;
  line.state.line_width = 3.0f;
  scene.draws.push_back(line);
  std::vector<std::string> rows(8, "........");
  rows[2] = rows[3] = rows[4] = "00000000";
  expect_owner_grid(render(scene), rows, 0);
}

TEST_F(VkReferenceTest, SmoothLinesAreNotSupportedOnLavapipe) {
  Scene scene = make_scene(8, 8);
  Draw line = window_triangles(scene, {{0, 3.5f}, {8, 3.5f}}, 0.5f);
  line.topology = Topology::LineList;
  line.state.line_mode = LineMode::RectangularSmooth;
  scene.draws.push_back(line);
  EXPECT_THROW(shared_renderer().render(scene), NotSupportedError);
  expect_no_validation_messages();
}

// A full-screen pair at z = 1.5 (beyond the far plane, compare ALWAYS). Depth clip follows
// !depthClampEnable unless VK_EXT_depth_clip_enable says otherwise (docs/lavapipe-rules.md §1.2); when not
// clipped, the stored depth is clamped to 1.0 (§3.4, with or without depth clamp).
TEST_F(VkReferenceTest, DepthClampAndExplicitDepthClip) {
  struct Case {
    bool clamp;
    std::optional<bool> clip;
    bool drawn;
  };
  for (const Case& c : {Case{false, std::nullopt, false}, Case{true, std::nullopt, true}, Case{true, true, false},
                        Case{false, false, true}}) {
    SCOPED_TRACE(fmt::format("clamp {} clip {}", c.clamp, c.clip ? int(*c.clip) : -1));
    Scene scene = make_scene(4, 4, DepthFormat::D32Sfloat);
    Draw draw = full_screen(scene, 1.5f);
    draw.state.depth.compare_op = CompareOp::Always;
    draw.state.depth_clamp = c.clamp;
    draw.state.depth_clip = c.clip;
    scene.draws.push_back(draw);
    const RenderResult result = render(scene);
    for (size_t i = 0; i < result.owner.size(); ++i) {
      ASSERT_EQ(result.owner[i] != kOwnerBackground, c.drawn) << "pixel " << i;
      ASSERT_EQ(result.depth_raw[i], 0x3F800000u) << "pixel " << i;  // 1.0: the clear or the clamp
    }
  }
}

// D32 constant bias on a z = 0.5 plane: r = 2^(e-23) with e = -1 (docs/lavapipe-rules.md §4.3), so a
// constant factor of 4 adds 2^-22 = 4 float steps at 0.5; a clamp of 2^-23 limits it to 2 steps.
TEST_F(VkReferenceTest, DepthBiasConstantAndClampOnD32) {
  for (const auto& [clamp, raw] : {std::pair{0.0f, 0x3F000004u}, std::pair{0x1p-23f, 0x3F000002u}}) {
    SCOPED_TRACE(clamp);
    Scene scene = make_scene(4, 4, DepthFormat::D32Sfloat);
    Draw draw = full_screen(scene, 0.5f);
    draw.state.depth_bias = DepthBias{true, 4.0f, 0.0f, clamp};
    scene.draws.push_back(draw);
    const RenderResult result = render(scene);
    for (uint32_t depth : result.depth_raw) ASSERT_EQ(depth, raw);
  }
}

TEST_F(VkReferenceTest, InvalidViewportIsInputErrorNotADriverCrash) {
  Scene scene = make_scene(8, 8);
  scene.viewport = Viewport{0, 0, 0, 8, 0, 1};
  scene.draws.push_back(full_screen(scene, 0.5f));
  try {
    shared_renderer().render(scene);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "$.viewport.width");
  }
  expect_no_validation_messages();
}

TEST_F(VkReferenceTest, PointOnPixelCentreCoversThatPixel) {
  Scene scene = make_scene(8, 8);
  Draw points = window_triangles(scene, {{3.5f, 2.5f}, {6.5f, 5.5f}}, 0.5f);
  points.topology = Topology::PointList;
  scene.draws.push_back(points);
  const RenderResult result = render(scene);
  std::vector<std::string> rows(8, "........");
  rows[2][3] = '0';
  rows[5][6] = '1';
  expect_owner_grid(result, rows, 0);
}

TEST_F(VkReferenceTest, DepthFormatNoneRendersOwnersWithoutDepth) {
  Scene scene = make_scene(8, 8, DepthFormat::None);
  scene.draws.push_back(full_screen(scene, 0.5f));
  scene.draws.push_back(full_screen(scene, 0.75f));  // no depth test without an attachment: overwrites
  const RenderResult result = render(scene);
  EXPECT_FALSE(result.has_depth());
  EXPECT_EQ(result.depth_format, DepthFormat::None);
  for (uint32_t owner : result.owner) EXPECT_EQ(owner_draw(owner), 1u);
}

TEST_F(VkReferenceTest, IndexedDrawUsesIndices) {
  Scene scene = make_scene(8, 8);
  Draw quad = window_triangles(scene, {{0, 0}, {8, 0}, {8, 8}, {0, 8}}, 0.5f);
  quad.indices = {0, 1, 3, 1, 2, 3};  // the same split as full_screen
  scene.draws.push_back(quad);
  expect_owner_grid(render(scene),
                    {"00000001", "00000011", "00000111", "00001111", "00011111", "00111111", "01111111", "11111111"},
                    0);
}

TEST_F(VkReferenceTest, PreparedSceneSubmitsRepeatedlyWithSameResult) {
  Scene scene = make_scene(8, 8);
  scene.draws.push_back(full_screen(scene, 0.5f));
  VulkanRenderer& renderer = shared_renderer();
  const std::unique_ptr<VulkanRenderer::Prepared> prepared = renderer.prepare(scene);
  EXPECT_GT(renderer.submit_and_wait_seconds(*prepared), 0.0);
  const RenderResult first = renderer.read_back(*prepared);
  EXPECT_GT(renderer.submit_and_wait_seconds(*prepared), 0.0);
  const RenderResult second = renderer.read_back(*prepared);
  EXPECT_EQ(first.owner, second.owner);
  EXPECT_EQ(first.depth_raw, second.depth_raw);
  EXPECT_EQ(first.owner, render(scene).owner);
  expect_no_validation_messages();
}

// The pipeline cache is bounded (a soak meets a new line width in most line scenes; lavapipe 26.2
// ran out of memory mappings with an unbounded cache): past the maximum the least recently used
// half goes, between frames only, and an evicted pipeline is made again with the same result.
TEST_F(VkReferenceTest, PipelineCacheStaysBoundedAndEvictedPipelinesRenderTheSame) {
  VkOptions options;
  options.max_cached_pipelines = 4;
  VulkanRenderer renderer(options);
  const auto wide_line = [](float width) {
    Scene scene = make_scene(8, 8);
    Draw line = window_triangles(scene, {{0, 3.5f}, {8, 3.5f}}, 0.5f);
    line.topology = Topology::LineList;
    line.state.line_width = width;
    scene.draws.push_back(line);
    return scene;
  };
  const RenderResult first = renderer.render(wide_line(3.0f));
  EXPECT_EQ(renderer.cached_pipelines(), 1u);
  for (int k = 1; k <= 4; ++k) renderer.render(wide_line(3.0f + 0.25f * float(k)));
  EXPECT_EQ(renderer.cached_pipelines(), 5u);  // trimmed before a frame, not after one
  // A prepared frame pins what it recorded: nothing is evicted while it is alive.
  {
    const std::unique_ptr<VulkanRenderer::Prepared> held = renderer.prepare(wide_line(5.0f));
    EXPECT_EQ(renderer.cached_pipelines(), 3u);  // 5 > 4: trimmed to the 2 most recent, then one made
    const std::unique_ptr<VulkanRenderer::Prepared> second = renderer.prepare(wide_line(5.5f));
    const std::unique_ptr<VulkanRenderer::Prepared> third = renderer.prepare(wide_line(6.0f));
    EXPECT_EQ(renderer.cached_pipelines(), 5u);
    renderer.submit_and_wait_seconds(*held);
    EXPECT_EQ(renderer.read_back(*held).owner, render(wide_line(5.0f)).owner);
  }
  const RenderResult again = renderer.render(wide_line(3.0f));  // evicted above, made again
  EXPECT_LE(renderer.cached_pipelines(), 4u);
  EXPECT_EQ(again.owner, first.owner);
  EXPECT_EQ(again.depth_raw, first.depth_raw);
}

TEST_F(VkReferenceTest, UnsupportedSampleCountIsNotSupported) {
  Scene scene = make_scene(8, 8);
  scene.samples = 2;  // lavapipe: framebuffer sample counts 1 and 4
  scene.draws.push_back(full_screen(scene, 0.5f));
  EXPECT_THROW(shared_renderer().render(scene), NotSupportedError);
  expect_no_validation_messages();
}

TEST_F(VkReferenceTest, IndexPastPositionsIsInputError) {
  Scene scene = make_scene(8, 8);
  scene.source_path = "scene.json";
  Draw draw = window_triangles(scene, {{0, 0}, {8, 0}, {0, 8}}, 0.5f);
  draw.indices = {0, 1, 3};
  scene.draws.push_back(draw);
  try {
    shared_renderer().render(scene);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.json");
    EXPECT_EQ(e.json_path(), "$.draws[0].indices[2]");
  }
  expect_no_validation_messages();
}

TEST_F(VkReferenceTest, UnknownDeviceNameListsDevices) {
  try {
    VulkanRenderer renderer(VkOptions{.device = "no-such-device-xyz", .validate = true});
    FAIL() << "expected EnvironmentError";
  } catch (const EnvironmentError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("no-such-device-xyz"), std::string::npos) << message;
    for (const DeviceInfo& d : list_vulkan_devices()) EXPECT_NE(message.find(d.name), std::string::npos) << message;
  }
}

TEST_F(VkReferenceTest, DeviceIndexOutOfRangeListsDevices) {
  try {
    VulkanRenderer renderer(VkOptions{.device = "999", .validate = false});
    FAIL() << "expected EnvironmentError";
  } catch (const EnvironmentError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("index 999"), std::string::npos) << message;
    EXPECT_NE(message.find("0: " + list_vulkan_devices().at(0).name), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace rastercmp
