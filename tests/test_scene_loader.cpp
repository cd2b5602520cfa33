// The scene loader (model/scene_io.cpp) against docs/scene-format.md: every feature parsed from
// tests/data/scenes/good/, and the catalogue of bad files in tests/data/bad_scenes/ whose
// expected JSON path and message are listed in tests/data/bad_scenes/expected.tsv.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "model/depth_format.hpp"
#include "model/errors.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace {

namespace fs = std::filesystem;

const fs::path kDataDir = fs::path(RASTERCMP_SOURCE_DIR) / "tests" / "data";
const fs::path kGoodDir = kDataDir / "scenes" / "good";
const fs::path kBadDir = kDataDir / "bad_scenes";
const fs::path kManifest = kBadDir / "expected.tsv";
constexpr size_t kMinBadScenes = 45;

Scene load_good(const std::string& file) { return load_scene_file((kGoodDir / file).string()); }

void expect_position(const glm::vec4& actual, const glm::vec4& expected) {
  for (int axis = 0; axis < 4; ++axis) EXPECT_FLOAT_EQ(actual[axis], expected[axis]) << "component " << axis;
}

// The message parse_scene gives for `text`, or "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "inline.json");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

// --- model/scene.cpp, model/render_result.cpp ---------------------------------------------

TEST(SceneModel, EnumNamesAreTheSceneFormatSpellings) {
  EXPECT_STREQ(to_string(DepthFormat::X8D24Unorm), "x8_d24_unorm");
  EXPECT_STREQ(to_string(Topology::TriangleFan), "triangle_fan");
  EXPECT_STREQ(to_string(CullMode::FrontAndBack), "front_and_back");
  EXPECT_STREQ(to_string(FrontFace::Clockwise), "cw");
  EXPECT_STREQ(to_string(PolygonMode::Point), "point");
  EXPECT_STREQ(to_string(LineMode::RectangularSmooth), "rectangular_smooth");
  EXPECT_STREQ(to_string(CompareOp::GreaterOrEqual), "greater_or_equal");
}

TEST(SceneModel, TopologyClassesAndDepthBits) {
  EXPECT_TRUE(is_triangle_topology(Topology::TriangleStrip));
  EXPECT_FALSE(is_triangle_topology(Topology::LineList));
  EXPECT_TRUE(is_line_topology(Topology::LineStrip));
  EXPECT_FALSE(is_line_topology(Topology::PointList));
  EXPECT_FALSE(is_triangle_topology(Topology::PointList));
  EXPECT_EQ(depth_bits(DepthFormat::None), 0u);
  EXPECT_EQ(depth_bits(DepthFormat::D16Unorm), 16u);
  EXPECT_EQ(depth_bits(DepthFormat::X8D24Unorm), 24u);
  EXPECT_EQ(depth_bits(DepthFormat::D32Sfloat), 32u);
}

// --- model/depth_format.hpp: the depth-format table ----------------------------------------

TEST(DepthFormatTable, EveryEnumValueHasItsEntryInEnumOrder) {
  ASSERT_EQ(kAllDepthFormats.size(), 4u);
  std::set<std::string> names;
  for (size_t i = 0; i < kAllDepthFormats.size(); ++i) {
    const DepthFormatInfo info = depth_format_info(kAllDepthFormats[i]);
    EXPECT_EQ(size_t(kAllDepthFormats[i]), i);
    EXPECT_EQ(info.format, kAllDepthFormats[i]) << i;
    EXPECT_STREQ(to_string(kAllDepthFormats[i]), info.name);
    names.insert(info.name);
  }
  EXPECT_EQ(names.size(), kAllDepthFormats.size());
  EXPECT_EQ(std::vector<DepthFormat>(kDepthFormats.begin(), kDepthFormats.end()),
            (std::vector<DepthFormat>{DepthFormat::D16Unorm, DepthFormat::X8D24Unorm, DepthFormat::D32Sfloat}));
}

TEST(DepthFormatTable, FactsOfEachFormat) {
  struct Expected {
    DepthFormat format;
    const char* name;
    uint32_t bits, raw_mask, bytes;
    DepthEncoding encoding;
    DepthConversion conversion;
    double mrd;  // as the code used it before the table: 1.0 / (2^n - 1) in double
  };
  for (const Expected& e : {
           Expected{DepthFormat::None, "none", 0, 0, 0, DepthEncoding::None, DepthConversion::None, 0.0},
           Expected{DepthFormat::D16Unorm, "d16_unorm", 16, 0xFFFFu, 2, DepthEncoding::Unorm,
                    DepthConversion::MagicNumber, 1.0 / 65535.0},
           Expected{DepthFormat::X8D24Unorm, "x8_d24_unorm", 24, 0xFFFFFFu, 4, DepthEncoding::Unorm,
                    DepthConversion::ScaleRound, 1.0 / 16777215.0},
           Expected{DepthFormat::D32Sfloat, "d32_sfloat", 32, 0xFFFFFFFFu, 4, DepthEncoding::Float,
                    DepthConversion::FloatBits, 0.0},
       }) {
    const DepthFormatInfo info = depth_format_info(e.format);
    SCOPED_TRACE(e.name);
    EXPECT_STREQ(info.name, e.name);
    EXPECT_EQ(info.bits, e.bits);
    EXPECT_EQ(depth_bits(e.format), e.bits);
    EXPECT_EQ(info.raw_mask, e.raw_mask);
    EXPECT_EQ(info.bytes_per_texel, e.bytes);
    EXPECT_EQ(info.encoding, e.encoding);
    EXPECT_EQ(info.conversion, e.conversion);
    EXPECT_EQ(info.mrd, e.mrd);  // bit for bit
    EXPECT_EQ(is_unorm(e.format), e.encoding == DepthEncoding::Unorm);
    EXPECT_EQ(is_float(e.format), e.encoding == DepthEncoding::Float);
    if (e.encoding == DepthEncoding::Unorm) {
      EXPECT_EQ(info.mrd, 1.0 / (std::ldexp(1.0, int(e.bits)) - 1.0));
      EXPECT_EQ(2.0 * info.mrd, 2.0 / (std::ldexp(1.0, int(e.bits)) - 1.0));  // r = 2 * mrd (§4.3)
      EXPECT_EQ(unorm_max(info), (uint64_t(1) << e.bits) - 1);
    }
  }
  // The constants of the conversions (docs/lavapipe-rules.md §3.5).
  const DepthFormatInfo d16 = depth_format_info(DepthFormat::D16Unorm);
  EXPECT_EQ(magic_scale(d16), 0.9999847412109375f);
  EXPECT_EQ(magic_bias(d16), 128.0f);
  EXPECT_EQ(float(unorm_max(depth_format_info(DepthFormat::X8D24Unorm))), 16777215.0f);
  EXPECT_EQ(depth_format_info(DepthFormat::D32Sfloat).mantissa_bits, 23u);
}

TEST(DepthFormatTable, FloatRIsTwoToTheExponentMinusTheMantissaBits) {
  const DepthFormatInfo d32 = depth_format_info(DepthFormat::D32Sfloat);
  EXPECT_EQ(float_depth_r(d32, 0.375), std::ldexp(1.0, -25));  // 0.375 = 1.5 * 2^-2
  EXPECT_EQ(float_depth_r(d32, 0.5), std::ldexp(1.0, -24));
  EXPECT_EQ(float_depth_r(d32, std::nextafter(0.5, 0.0)), std::ldexp(1.0, -25));
  EXPECT_EQ(float_depth_r(d32, 1.0), std::ldexp(1.0, -23));
  EXPECT_EQ(float_depth_r(d32, 0.0), std::ldexp(1.0, -149));  // e = -126 at least
  EXPECT_EQ(float_depth_r(d32, 1e-45), std::ldexp(1.0, -149));
  EXPECT_EQ(float_depth_r(d32, INFINITY), std::ldexp(1.0, -149));
  EXPECT_EQ(float_depth_r(d32, NAN), std::ldexp(1.0, -149));
}

TEST(RenderResult, DepthRawToValueDecodesEachFormat) {
  EXPECT_EQ(depth_raw_to_value(DepthFormat::D16Unorm, 0), 0.0);
  EXPECT_EQ(depth_raw_to_value(DepthFormat::D16Unorm, 65535), 1.0);
  EXPECT_EQ(depth_raw_to_value(DepthFormat::D16Unorm, 21845), 21845.0 / 65535.0);
  EXPECT_EQ(depth_raw_to_value(DepthFormat::X8D24Unorm, 0xFFFFFF), 1.0);
  EXPECT_EQ(depth_raw_to_value(DepthFormat::X8D24Unorm, 0xAB000001), 1.0 / 16777215.0);  // X8 bits ignored
  EXPECT_EQ(depth_raw_to_value(DepthFormat::D32Sfloat, std::bit_cast<uint32_t>(0.375f)), 0.375);
  EXPECT_THROW(depth_raw_to_value(DepthFormat::None, 0), std::invalid_argument);
}

// --- valid scenes -------------------------------------------------------------------------

TEST(SceneLoader, MinimalSceneTakesEveryDefault) {
  const Scene scene = load_good("minimal.json");
  EXPECT_EQ(scene.name, "minimal");  // the file stem
  EXPECT_EQ(scene.description, "");
  EXPECT_EQ(scene.source_path, (kGoodDir / "minimal.json").string());
  EXPECT_EQ(scene.width, 64u);
  EXPECT_EQ(scene.height, 64u);
  EXPECT_EQ(scene.depth_format, DepthFormat::D32Sfloat);
  EXPECT_EQ(scene.depth_clear, 1.0f);
  EXPECT_EQ(scene.samples, 1u);
  EXPECT_FALSE(scene.viewport || scene.scissor || scene.camera);
  EXPECT_TRUE(scene.methods.empty());
  ASSERT_EQ(scene.draws.size(), 1u);
  const Draw& draw = scene.draws[0];
  EXPECT_EQ(draw.topology, Topology::TriangleList);
  EXPECT_TRUE(draw.indices.empty());
  ASSERT_EQ(draw.positions_clip.size(), 3u);
  expect_position(draw.positions_clip[2], {0.0f, 0.5f, 0.5f, 1.0f});
  const RasterState& state = draw.state;
  EXPECT_EQ(state.cull_mode, CullMode::None);
  EXPECT_EQ(state.front_face, FrontFace::CounterClockwise);
  EXPECT_EQ(state.polygon_mode, PolygonMode::Fill);
  EXPECT_EQ(state.line_mode, LineMode::Default);
  EXPECT_EQ(state.line_width, 1.0f);
  EXPECT_TRUE(state.depth.test_enable && state.depth.write_enable);
  EXPECT_EQ(state.depth.compare_op, CompareOp::Less);
  EXPECT_FALSE(state.depth_bias.enable || state.depth_clamp || state.depth_clip.has_value());
}

TEST(SceneLoader, EveryTopLevelKey) {
  const Scene scene = load_good("every_top_level_key.json");
  EXPECT_EQ(scene.name, "rastercmp.model.every_top_level_key");
  EXPECT_EQ(scene.description, "every top-level key set to a value other than its default");
  EXPECT_EQ(scene.width, 96u);
  EXPECT_EQ(scene.height, 48u);
  EXPECT_EQ(scene.depth_format, DepthFormat::D16Unorm);
  EXPECT_EQ(scene.depth_clear, 0.75f);
  EXPECT_EQ(scene.samples, 4u);
  ASSERT_TRUE(scene.viewport && scene.scissor);
  EXPECT_EQ(scene.viewport->x, 4.0f);
  EXPECT_EQ(scene.viewport->y, 2.0f);
  EXPECT_EQ(scene.viewport->width, 80.0f);
  EXPECT_EQ(scene.viewport->height, -40.0f);
  EXPECT_EQ(scene.viewport->min_depth, 0.25f);
  EXPECT_EQ(scene.viewport->max_depth, 0.75f);
  EXPECT_EQ(scene.scissor->x, 1);
  EXPECT_EQ(scene.scissor->y, 2);
  EXPECT_EQ(scene.scissor->width, 30u);
  EXPECT_EQ(scene.scissor->height, 20u);
  ASSERT_EQ(scene.methods.size(), 2u);
  EXPECT_EQ(scene.methods[0].stage, "clip");
  EXPECT_EQ(scene.methods[0].name, "sutherland_hodgman");
  EXPECT_EQ(scene.methods[1].stage, "fill");
  EXPECT_EQ(scene.methods[1].name, "scanline");
  ASSERT_EQ(scene.draws.size(), 1u);
  EXPECT_EQ(scene.draws[0].state.cull_mode, CullMode::Back);
  EXPECT_EQ(scene.draws[0].state.depth.compare_op, CompareOp::LessOrEqual);
  expect_position(scene.draws[0].positions_clip[1], {1, -1, 0.5f, 2});
}

TEST(SceneLoader, EveryDrawStateKey) {
  const Scene scene = load_good("draw_state.json");
  ASSERT_EQ(scene.draws.size(), 2u);
  const Draw& draw = scene.draws[0];
  EXPECT_EQ(draw.name, "every state key");
  EXPECT_EQ(draw.topology, Topology::TriangleStrip);
  const RasterState& state = draw.state;
  EXPECT_EQ(state.cull_mode, CullMode::FrontAndBack);
  EXPECT_EQ(state.front_face, FrontFace::Clockwise);
  EXPECT_EQ(state.polygon_mode, PolygonMode::Point);
  EXPECT_EQ(state.line_mode, LineMode::Rectangular);
  EXPECT_EQ(state.line_width, 2.5f);
  EXPECT_FALSE(state.depth.test_enable || state.depth.write_enable);
  EXPECT_EQ(state.depth.compare_op, CompareOp::GreaterOrEqual);
  EXPECT_TRUE(state.depth_bias.enable);
  EXPECT_EQ(state.depth_bias.constant_factor, -3.0f);
  EXPECT_EQ(state.depth_bias.slope_factor, 0.5f);
  EXPECT_EQ(state.depth_bias.clamp, -0.125f);
  EXPECT_TRUE(state.depth_clamp);
  EXPECT_EQ(state.depth_clip, std::optional<bool>(true));
  EXPECT_EQ(scene.draws[1].name, "all defaults");
  EXPECT_EQ(scene.draws[1].state.cull_mode, CullMode::None);
  EXPECT_FALSE(scene.draws[1].state.depth_clamp);
}

TEST(SceneLoader, DefaultsApplyBeforeEachDrawsOwnKeys) {
  const Scene scene = load_good("defaults_and_depth_bias.json");
  ASSERT_EQ(scene.draws.size(), 4u);
  const RasterState& inherits = scene.draws[0].state;
  EXPECT_EQ(inherits.cull_mode, CullMode::Back);
  EXPECT_EQ(inherits.line_width, 4.0f);
  EXPECT_TRUE(inherits.depth_clamp);
  EXPECT_FALSE(inherits.depth_clip_enabled());  // absent depth_clip: !depth_clamp
  EXPECT_TRUE(inherits.depth_bias.enable);
  EXPECT_EQ(inherits.depth_bias.constant_factor, 1.5f);
  EXPECT_EQ(inherits.depth_bias.slope_factor, 2.0f);
  EXPECT_EQ(inherits.depth_bias.clamp, 0.01f);
  EXPECT_FALSE(scene.draws[1].state.depth_bias.enable);
  const DepthBias& own = scene.draws[2].state.depth_bias;  // replaces the default bias as a whole
  EXPECT_TRUE(own.enable);
  EXPECT_EQ(own.constant_factor, 0.0f);
  EXPECT_EQ(own.slope_factor, -1.0f);
  EXPECT_EQ(own.clamp, 0.0f);
  const RasterState& own_cull = scene.draws[3].state;
  EXPECT_EQ(own_cull.cull_mode, CullMode::None);
  EXPECT_EQ(own_cull.line_width, 4.0f);
  EXPECT_EQ(own_cull.depth_clip, std::optional<bool>(false));
}

// Pixels → clip inverts the viewport transform x_f = o_x + p_x/2 * x_c/w (Vulkan spec).
TEST(SceneLoader, PixelsSpaceInvertsTheWholeFramebufferViewport) {
  const Scene scene = load_good("pixels_space.json");
  const auto& pos = scene.draws.at(0).positions_clip;
  ASSERT_EQ(pos.size(), 3u);
  // o = (32, 16), p/2 = (32, 16), depth 0..1.
  expect_position(pos[0], {-0.5f, -0.5f, 0.25f, 1});
  expect_position(pos[1], {0.5f, -0.5f, 0.25f, 1});
  expect_position(pos[2], {0.0f, 1.0f, 1.5f, 2});  // w = 2 scales x, y, z
}

TEST(SceneLoader, PixelsSpaceWithAnOffsetFlippedViewport) {
  const Scene scene = load_good("pixels_viewport.json");
  const auto& pos = scene.draws.at(0).positions_clip;
  ASSERT_EQ(pos.size(), 3u);
  // o = (8 + 16, 4 - 8) = (24, -4), p/2 = (16, -8), o_z = 0.25, p_z = 0.5.
  expect_position(pos[0], {0.0f, -0.5f, 0.5f, 1});
  expect_position(pos[1], {-1.0f, 0.0f, 0.0f, 1});
  expect_position(pos[2], {4.0f, 4.0f, 4.0f, 4});
  const Viewport vp = scene.effective_viewport();
  for (const glm::vec4& p : pos) {  // and back through the viewport transform
    const float x_f = vp.x + vp.width / 2 + vp.width / 2 * (p.x / p.w);
    const float y_f = vp.y + vp.height / 2 + vp.height / 2 * (p.y / p.w);
    EXPECT_TRUE(x_f == 24 || x_f == 8 || x_f == 40) << x_f;
    EXPECT_TRUE(y_f == 0 || y_f == -4 || y_f == -12) << y_f;
  }
}

// eye (0,0,2) looking at the origin, fov 90 (f = 1/tan 45° = 1), near 1, far 3, aspect 1:
// view z = z - 2; x_c = x, y_c = -y (Vulkan y flip), z_c = -1.5 * z_view - 1.5, w = -z_view.
TEST(SceneLoader, WorldSpaceMatchesHandComputedClipPositions) {
  const Scene scene = load_good("world_camera.json");
  ASSERT_TRUE(scene.camera);
  EXPECT_EQ(scene.camera->fov_y_degrees, 90.0f);
  EXPECT_EQ(scene.camera->near_plane, 1.0f);
  EXPECT_EQ(scene.camera->far_plane, 3.0f);
  const auto& pos = scene.draws.at(0).positions_clip;
  ASSERT_EQ(pos.size(), 3u);
  expect_position(pos[0], {0, 0, 1.5f, 2});
  expect_position(pos[1], {1, -1, 1.5f, 2});
  expect_position(pos[2], {-1, 0, 3.0f, 3});  // on the far plane: depth z/w = 1
}

TEST(SceneLoader, WorldSpaceUsesTheViewportAspect) {
  const Scene scene = load_good("world_camera_wide.json");  // 128 x 64: aspect 2, camera defaults
  ASSERT_TRUE(scene.camera);
  EXPECT_EQ(scene.camera->target, glm::vec3(0, 0, 0));
  EXPECT_EQ(scene.camera->up, glm::vec3(0, 1, 0));
  const auto& pos = scene.draws.at(0).positions_clip;
  expect_position(pos[0], {0.5f, -1, 1.5f, 2});
  expect_position(pos[1], {-0.5f, 0, 1.5f, 2});
  expect_position(pos[2], {0, 1, 1.5f, 2});
}

TEST(SceneLoader, LinesAndMsaa) {
  const Scene scene = load_good("lines_and_msaa.json");
  EXPECT_EQ(scene.samples, 4u);
  EXPECT_EQ(scene.depth_format, DepthFormat::X8D24Unorm);
  ASSERT_EQ(scene.draws.size(), 3u);
  EXPECT_EQ(scene.draws[0].topology, Topology::LineList);
  EXPECT_EQ(scene.draws[0].state.line_mode, LineMode::Bresenham);
  EXPECT_EQ(scene.draws[0].state.line_width, 3.0f);
  EXPECT_EQ(scene.draws[0].vertex_count(), 4u);
  EXPECT_EQ(scene.draws[1].topology, Topology::LineStrip);
  EXPECT_EQ(scene.draws[1].state.line_mode, LineMode::RectangularSmooth);
  EXPECT_EQ(scene.draws[1].state.line_width, 1.5f);
  EXPECT_EQ(scene.draws[2].state.polygon_mode, PolygonMode::Line);
}

TEST(SceneLoader, CountShortensTheDraw) {
  const Scene scene = load_good("indexed_count.json");
  ASSERT_EQ(scene.draws.size(), 3u);
  EXPECT_EQ(scene.draws[0].indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(scene.draws[0].positions_clip.size(), 4u);  // indexed: the positions stay
  EXPECT_EQ(scene.draws[1].indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));
  EXPECT_EQ(scene.draws[2].indices.size(), 0u);
  EXPECT_EQ(scene.draws[2].vertex_count(), 3u);
  expect_position(scene.draws[2].positions_clip.back(), {-1, 1, 0.5f, 1});
}

TEST(SceneLoader, NonFiniteValuesWhenAllowed) {
  const Scene scene = load_good("non_finite.json");
  const auto& pos = scene.draws.at(0).positions_clip;
  EXPECT_TRUE(std::isnan(pos[0].x));
  EXPECT_EQ(pos[1].y, INFINITY);
  EXPECT_EQ(pos[2].x, -INFINITY);
  const auto& second = scene.draws.at(1).positions_clip;
  EXPECT_EQ(second[0].w, 0.0f);
  EXPECT_EQ(second[1].x, INFINITY);  // 1e39 does not fit a float
}

TEST(SceneLoader, EveryTopology) {
  const Scene scene = load_good("topologies.json");
  const std::vector<Topology> expected = {Topology::PointList,    Topology::LineList,      Topology::LineStrip,
                                          Topology::TriangleList, Topology::TriangleStrip, Topology::TriangleFan};
  ASSERT_EQ(scene.draws.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(scene.draws[i].topology, expected[i]) << i;
}

TEST(SceneLoader, EveryDepthFormatAndCompareOpName) {
  for (const DepthFormat format : kAllDepthFormats) {
    const std::string text = std::string(R"({"depth_format": ")") + to_string(format) +
                             R"(", "draws": [{"topology": "point_list", "positions": [[0, 0, 0]]}]})";
    EXPECT_EQ(parse_scene(text, "formats.json").depth_format, format) << to_string(format);
  }
  for (const CompareOp op : {CompareOp::Never, CompareOp::Less, CompareOp::Equal, CompareOp::LessOrEqual,
                             CompareOp::Greater, CompareOp::NotEqual, CompareOp::GreaterOrEqual, CompareOp::Always}) {
    const std::string text = std::string(R"({"draws": [{"depth_compare": ")") + to_string(op) +
                             R"(", "topology": "point_list", "positions": [[0, 0, 0]]}]})";
    EXPECT_EQ(parse_scene(text, "ops.json").draws[0].state.depth.compare_op, op) << to_string(op);
  }
}

TEST(SceneLoader, EveryGoodSceneLoads) {
  size_t loaded = 0;
  for (const auto& entry : fs::directory_iterator(kGoodDir)) {
    EXPECT_NO_THROW(load_scene_file(entry.path().string())) << entry.path();
    ++loaded;
  }
  EXPECT_GE(loaded, 12u);
}

TEST(SceneLoader, UnreadableFilesAreInputErrors) {
  const std::string missing = (kDataDir / "no_such_scene.json").string();
  try {
    load_scene_file(missing);
    FAIL() << "a missing file loaded";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), missing);
    EXPECT_NE(error.expected().find("No such file"), std::string::npos) << error.what();
  }
  try {
    load_scene_file(kGoodDir.string());
    FAIL() << "a directory loaded";
  } catch (const InputError& error) {
    EXPECT_EQ(error.expected(), "expected a scene file, found a directory");
  }
}

// Scene files are read with a cap (model/scene_io.hpp kMaxSceneFileBytes, docs/scene-format.md):
// a file one byte over it (a sparse file), or one that never ends, is refused before parsing.
TEST(SceneLoader, FilesAboveTheSizeLimitAreRefusedBeforeParsing) {
  const fs::path dir = fs::temp_directory_path() / ("rastercmp_size_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const auto sparse_file = [&](const std::string& name, size_t size) {
    std::ofstream(dir / name, std::ios::binary).close();
    fs::resize_file(dir / name, size);
    return (dir / name).string();
  };
  const std::string over_limit = sparse_file("over_limit.json", kMaxSceneFileBytes + 1);
  for (const std::string& path : {over_limit, std::string("/dev/zero")}) {
    try {
      load_scene_file(path);
      ADD_FAILURE() << path << " loaded";
    } catch (const InputError& error) {
      EXPECT_EQ(error.file(), path);
      EXPECT_EQ(error.json_path(), "$");
      EXPECT_EQ(error.expected(), "expected a scene file of at most 64 MiB, found more");
    }
  }
  fs::remove_all(dir);
}

// A long key or string is cut in messages, with its size: a megabyte key is not echoed whole.
TEST(SceneLoader, LongKeysAndStringsAreCutInMessages) {
  const std::string key(1 << 20, 'k');
  const std::string unknown = error_of("{\"" + key + "\": 1, \"draws\": []}");
  EXPECT_LT(unknown.size(), 400u) << unknown.substr(0, 400);
  EXPECT_NE(unknown.find("... (1048576 bytes)"), std::string::npos) << unknown.substr(0, 400);
  EXPECT_NE(unknown.find("inline.json: $[\"kkkk"), std::string::npos) << unknown.substr(0, 400);
  const std::string value = error_of("{\"name\": \"" + std::string(100000, 'A') + "\", \"draws\": []}");
  EXPECT_LT(value.size(), 400u) << value.substr(0, 400);
  EXPECT_NE(value.find("... (100000 bytes)"), std::string::npos) << value.substr(0, 400);
}

TEST(SceneLoader, SyntaxErrorsGiveLineColumnAndByteOffset) {
  const std::string syntax = error_of("{\n  \"width\" 8\n}");
  EXPECT_EQ(syntax.rfind("inline.json: $: expected valid JSON, found a syntax error at line 2, column 11 "
                         "(byte offset 12): ",
                         0),
            0u)
      << syntax;
  EXPECT_EQ(syntax.find("truncated"), std::string::npos) << syntax;
  const std::string truncated = error_of("{\n  \"width\": 8,\n  \"draws\": [");
  EXPECT_NE(truncated.find("at line 3, column 13 (byte offset 28): "), std::string::npos) << truncated;
  EXPECT_NE(truncated.find("(the file ends early: truncated?)"), std::string::npos) << truncated;
  // Columns count characters: the two-byte "é" is one column.
  EXPECT_EQ(error_of("[\"\xC3\xA9\", \"\xC3\"]"),
            "inline.json: $: expected UTF-8 text, found the invalid UTF-8 byte 0xC3 at line 1, column 8 "
            "(byte offset 8)");
}

TEST(SceneLoader, ParseSceneNamesTheSceneAfterTheGivenFile) {
  const std::string text = R"({"draws": [{"topology": "point_list", "positions": [[0, 0, 0]]}]})";
  EXPECT_EQ(parse_scene(text, "some/dir/fill.top_left.json").name, "fill.top_left");
  EXPECT_NE(error_of(R"({"draws": [{"topology": "point_list", "positions": [[0, 0, 0]]}], "name": "x-y"})"), "");
}

// Every ```json block of docs/scene-format.md is a valid scene, a valid draw, or a valid
// top-level or draw key ("key": value), so the examples cannot drift from the loader.
TEST(SceneLoader, EveryDocumentationExampleParses) {
  std::ifstream in(fs::path(RASTERCMP_SOURCE_DIR) / "docs" / "scene-format.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string point_draw = R"({"topology": "point_list", "positions": [[0, 0, 0]])";
  size_t examples = 0;
  for (size_t start = doc.find("```json\n"); start != std::string::npos; start = doc.find("```json\n", start)) {
    start += 8;
    const size_t end = doc.find("```", start);
    ASSERT_NE(end, std::string::npos);
    const std::string block = doc.substr(start, end - start);
    const std::vector<std::string> candidates = {block, "{\"draws\": [" + block + "]}",
                                                 "{" + block + ", \"draws\": [" + point_draw + "}]}",
                                                 "{\"draws\": [" + point_draw + ", " + block + "}]}"};
    const bool parses = std::any_of(candidates.begin(), candidates.end(),
                                    [](const std::string& text) { return error_of(text).empty(); });
    EXPECT_TRUE(parses) << block << "\n" << error_of(block);
    ++examples;
  }
  EXPECT_GE(examples, 12u);
}

// --- the bad-scene catalogue ----------------------------------------------------------------

struct BadCase {
  std::string file;
  std::string json_path;
  std::string substring;
};

// expected.tsv: file<TAB>json path<TAB>substring of the message; '#' starts a comment line.
// A line without exactly three fields becomes a case that fails, naming the line.
std::vector<BadCase> read_manifest() {
  std::vector<BadCase> cases;
  std::ifstream in(kManifest);
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    for (size_t start = 0;;) {
      const size_t tab = line.find('\t', start);
      fields.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
      if (tab == std::string::npos) break;
      start = tab + 1;
    }
    if (fields.size() != 3) fields = {"malformed_manifest_line_" + std::to_string(number), "", ""};
    cases.push_back(BadCase{fields[0], fields[1], fields[2]});
  }
  return cases;
}

class BadScene : public testing::TestWithParam<BadCase> {};

TEST_P(BadScene, FailsWithItsPathAndMessage) {
  const BadCase& bad = GetParam();
  const std::string path = (kBadDir / bad.file).string();
  ASSERT_TRUE(fs::is_regular_file(path)) << path;
  try {
    load_scene_file(path);
    FAIL() << path << " loaded without an error";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_EQ(error.json_path(), bad.json_path) << message;
    EXPECT_EQ(error.expected().rfind("expected ", 0), 0u) << message;
    EXPECT_NE(error.expected().find(bad.substring), std::string::npos) << message;
  }
}

std::string case_name(const testing::TestParamInfo<BadCase>& info) {
  std::string name = fs::path(info.param.file).stem().string();
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadScene, testing::ValuesIn(read_manifest()), case_name);

TEST(BadSceneCatalogue, ManifestAndFolderAgree) {
  const std::vector<BadCase> cases = read_manifest();
  EXPECT_GE(cases.size(), kMinBadScenes);
  std::set<std::string> listed;
  for (const BadCase& bad : cases) {
    EXPECT_TRUE(listed.insert(bad.file).second) << bad.file << " is listed twice";
    EXPECT_TRUE(fs::is_regular_file(kBadDir / bad.file)) << bad.file << " is listed but missing";
  }
  for (const auto& entry : fs::directory_iterator(kBadDir)) {
    const std::string file = entry.path().filename().string();
    if (entry.path() != kManifest) {
      EXPECT_TRUE(listed.count(file)) << file << " is not in expected.tsv";
    }
  }
}

}  // namespace
}  // namespace rastercmp
