// Each classic method, selected on a real scene, pinned with numbers against the exact path
// (docs/methods.md "Selecting a method"; scenes in scenes/methods/).
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cpu_raster/classic/classic_clip.hpp"
#include "cpu_raster/classic/classic_explain.hpp"
#include "cpu_raster/classic/classic_methods.hpp"
#include "cpu_raster/classic/method_registry.hpp"
#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/viewport.hpp"
#include "model/errors.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace {

Scene method_scene(const std::string& relative) {
  return load_scene_file(std::string(RASTERCMP_SOURCE_DIR) + "/scenes/methods/" + relative + ".json");
}

RenderResult render_with(const Scene& scene, std::vector<MethodChoice> methods) {
  CpuOptions options;
  options.fma = true;
  options.methods = std::move(methods);
  return options.methods.empty() ? render_cpu(scene, options) : render_classic(scene, options);
}

size_t owner_differences(const RenderResult& a, const RenderResult& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.owner.size(); ++i) n += a.owner[i] != b.owner[i];
  return n;
}

size_t depth_differences(const RenderResult& a, const RenderResult& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.depth_raw.size(); ++i) n += a.depth_raw[i] != b.depth_raw[i];
  return n;
}

// Pixels covered by both triangles of the quad, each rendered alone.
size_t double_covered(const Scene& quad, const std::vector<MethodChoice>& methods) {
  std::vector<RenderResult> alone;
  for (size_t t = 0; t < 2; ++t) {
    Scene one = quad;
    one.draws[0].positions_clip.assign(quad.draws[0].positions_clip.begin() + 3 * t,
                                       quad.draws[0].positions_clip.begin() + 3 * t + 3);
    alone.push_back(render_with(one, methods));
  }
  size_t both = 0;
  for (size_t i = 0; i < alone[0].owner.size(); ++i)
    both += alone[0].owner[i] != kOwnerBackground && alone[1].owner[i] != kOwnerBackground;
  return both;
}

TEST(ClassicFill, FloatEdgeDoubleCoversExactlyTheSharedDiagonal) {
  const Scene quad = method_scene("fill/float_edge/shared_edge_quad");
  EXPECT_EQ(double_covered(quad, {{"fill", "float_edge"}}), 16u);  // centres (k+.5, k+.5), k = 4..19
  EXPECT_EQ(double_covered(quad, {{"fill", "exact"}}), 0u);
  EXPECT_EQ(double_covered(quad, {{"fill", "scanline"}}), 0u);
  EXPECT_EQ(owner_differences(render_with(quad, {{"fill", "float_edge"}}), render_with(quad, {})), 16u);
}

TEST(ClassicVisibility, PainterFailsOnCyclicSticksWhereBspMatchesTheZBuffer) {
  const Scene sticks = method_scene("visibility/painter/cyclic_sticks");
  const RenderResult zbuffer = render_with(sticks, {});
  EXPECT_GT(owner_differences(render_with(sticks, {{"visibility", "painter"}}), zbuffer), 0u);
  EXPECT_EQ(owner_differences(render_with(sticks, {{"visibility", "bsp"}}), zbuffer), 0u);
  EXPECT_EQ(depth_differences(render_with(sticks, {{"visibility", "bsp"}}), zbuffer), 0u);
}

TEST(ClassicDepth, NoFmaMovesDepthBitsButNotCoverageOnASteepPlane) {
  const Scene steep = method_scene("depth/no_fma/steep_plane");
  const RenderResult exact = render_with(steep, {});
  const RenderResult unfused = render_with(steep, {{"depth", "no_fma"}});
  EXPECT_EQ(owner_differences(unfused, exact), 0u);
  EXPECT_GT(depth_differences(unfused, exact), 0u);
}

TEST(ClassicLine, DdaAndBresenhamAddTheEndPixelsVulkanLeavesOut) {
  const Scene lines = method_scene("line/dda/inside_endpoints");
  const RenderResult exact = render_with(lines, {});
  EXPECT_GT(owner_differences(render_with(lines, {{"line", "dda"}}), exact), 0u);
  EXPECT_GT(owner_differences(render_with(lines, {{"line", "bresenham"}}), exact), 0u);
}

TEST(ClassicClip, CohenSutherlandNeedsSeveralPassesWhereLiangBarskyNeedsOne) {
  const Scene scene = method_scene("clip/liang_barsky/clipped_lines");
  const cpu::ViewportTransform viewport = cpu::make_viewport_transform(scene.effective_viewport());
  const auto& p = scene.draws[0].positions_clip;
  const auto clip = [&](size_t first, cpu::classic::LineClipper clipper) {
    const std::array<cpu::ClipVertex, 2> line{cpu::make_clip_vertex(p[first], viewport, true, true),
                                              cpu::make_clip_vertex(p[first + 1], viewport, true, true)};
    return cpu::classic::clip_line_classic(line, viewport, true, clipper);
  };
  // Line 1 crosses the framebuffer, entering and leaving through sides it crossed outside first.
  const auto cs = clip(2, cpu::classic::LineClipper::CohenSutherland3d);
  const auto lb = clip(2, cpu::classic::LineClipper::LiangBarsky);
  ASSERT_TRUE(cs.visible && lb.visible);
  EXPECT_GE(cs.passes, 3);
  EXPECT_EQ(lb.passes, 1);
  EXPECT_GT(cs.clips, 2);  // more cuts than the two endpoints that move
  EXPECT_EQ(lb.clips, 2);
  // Line 0 passes the corner outside: Cohen–Sutherland cuts before it can reject.
  const auto cs_miss = clip(0, cpu::classic::LineClipper::CohenSutherland3d);
  const auto lb_miss = clip(0, cpu::classic::LineClipper::LiangBarsky);
  EXPECT_FALSE(cs_miss.visible || lb_miss.visible);
  EXPECT_GE(cs_miss.passes, 2);
  EXPECT_EQ(lb_miss.passes, 1);
}

TEST(ClassicCull, NormalDotViewIgnoresTheViewportFlip) {
  const Scene normal = method_scene("cull/normal_dot_view/back");
  const Scene flipped = method_scene("cull/normal_dot_view/flipped_viewport");
  EXPECT_EQ(owner_differences(render_with(normal, {{"cull", "normal_dot_view"}}), render_with(normal, {})), 0u);
  EXPECT_GT(owner_differences(render_with(flipped, {{"cull", "normal_dot_view"}}), render_with(flipped, {})), 0u);
}

// Every stage at exact is the exact path, bit for bit, on every built-in scene (the suite and the
// method scenes): the same denormal mode, draw chunks and set-up modes (docs/lavapipe-rules.md §1.5,
// §7.10, §7.11), so a classic method's count on the suite measures that method alone. A scene the
// exact path refuses, the classic route refuses too.
TEST(ClassicMethods, AllExactIsTheExactPathBitForBitOnEveryBuiltInScene) {
  const std::vector<MethodChoice> all_exact{{"clip", "exact"},  {"fill", "exact"},         {"line", "exact"},
                                            {"depth", "exact"}, {"visibility", "zbuffer"}, {"cull", "exact"}};
  size_t compared = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(RASTERCMP_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    const Scene scene = load_scene_file(entry.path().string());
    SCOPED_TRACE(entry.path().string());
    std::optional<RenderResult> exact;
    try {
      exact = render_with(scene, {});
    } catch (const NotSupportedError&) {
      EXPECT_THROW(render_with(scene, all_exact), NotSupportedError);
      continue;
    }
    const RenderResult classic = render_with(scene, all_exact);
    EXPECT_EQ(classic.owner, exact->owner);
    EXPECT_EQ(classic.depth_raw, exact->depth_raw);
    ++compared;
  }
  EXPECT_GT(compared, 150u);
}

TEST(ClassicMethods, UnknownStageOrNameIsAUsageErrorListingTheValidOnes) {
  const Scene scene = method_scene("fill/scanline/fan");
  try {
    render_with(scene, {{"fill", "magic"}});
    FAIL() << "fill=magic was accepted";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("exact, scanline, even_odd, winding, float_edge, flood"),
              std::string::npos);
  }
  try {
    render_with(scene, {{"shading", "gouraud"}});
    FAIL() << "shading=gouraud was accepted";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("clip, cull, fill, line, depth, visibility, snap, tie_break"),
              std::string::npos);
  }
  CpuOptions options;
  options.methods = {{"snap", "round_half_away"}};
  EXPECT_FALSE(uses_classic_methods(options));
  options.methods.push_back({"fill", "scanline"});
  EXPECT_TRUE(uses_classic_methods(options));
}

// --- The registry (cpu_raster/classic/method_registry.hpp) ---

TEST(MethodRegistry, EveryNameParsesAndEveryStageHasItsDefaultFirst) {
  using namespace cpu::classic;
  for (const MethodInfo& m : method_registry()) {
    const MethodChoice choice{std::string(m.stage), std::string(m.name)};
    EXPECT_NO_THROW(parse_classic_methods({choice})) << m.stage << "=" << m.name;
    EXPECT_FALSE(m.summary.empty()) << m.name;
    EXPECT_FALSE(m.doc.empty()) << m.name;
  }
  const std::map<std::string, std::string> defaults{{"clip", "exact"},
                                                    {"cull", "exact"},
                                                    {"fill", "exact"},
                                                    {"line", "exact"},
                                                    {"depth", "exact"},
                                                    {"visibility", "zbuffer"},
                                                    {"snap", "round_nearest_even"},
                                                    {"tie_break", "top_left"}};
  for (const StageInfo& s : method_stages()) {
    const std::string names = method_names(s.stage);
    EXPECT_EQ(names.substr(0, names.find(',')), defaults.at(std::string(s.stage))) << s.stage;
  }
  // Every method of the notes has a section title; only lavapipe's own rules have none.
  size_t from_notes = 0;
  for (const MethodInfo& m : method_registry()) from_notes += !m.notes.empty();
  EXPECT_EQ(from_notes, 23u);
}

// README.md's "Methods" table lists exactly what --method accepts.
TEST(MethodRegistry, ReadmeListsExactlyTheRegistry) {
  std::ifstream readme(std::string(RASTERCMP_SOURCE_DIR) + "/README.md");
  ASSERT_TRUE(readme.good());
  std::map<std::string, std::vector<std::string>> listed;
  bool in_section = false;
  const std::regex row("^\\| `([a-z_]+)` \\| (.*) \\|$"), name("`([a-z0-9_]+)`");
  for (std::string line; std::getline(readme, line);) {
    if (line.rfind("## ", 0) == 0) in_section = line == "## Methods";
    std::smatch m;
    if (!in_section || !std::regex_match(line, m, row)) continue;
    const std::string names = m[2];
    for (std::sregex_iterator it(names.begin(), names.end(), name), end; it != end; ++it)
      listed[m[1]].push_back((*it)[1]);
  }
  std::map<std::string, std::vector<std::string>> registry;
  for (const cpu::classic::MethodInfo& m : cpu::classic::method_registry())
    registry[std::string(m.stage)].push_back(std::string(m.name));
  EXPECT_EQ(listed, registry);
}

std::string inapplicable(const Scene& scene, const MethodChoice& choice) {
  return cpu::classic::method_inapplicable(scene, choice).value_or("");
}

TEST(MethodRegistry, AMethodThatCannotRunNamesTheScenesFeature) {
  Scene fan = method_scene("fill/scanline/fan");
  EXPECT_EQ(inapplicable(fan, {"fill", "flood"}), "");
  EXPECT_NE(inapplicable(fan, {"depth", "pseudo_depth_75"}).find("$.draws[0].positions[0] has w = 1"),
            std::string::npos);
  fan.samples = 4;
  EXPECT_NE(inapplicable(fan, {"fill", "scanline"}).find("the scene has 4 samples"), std::string::npos);
  EXPECT_EQ(inapplicable(fan, {"depth", "no_fma"}), "");  // the plane, per sample
  const Scene lines = method_scene("clip/liang_barsky/clipped_lines");
  EXPECT_NE(inapplicable(lines, {"visibility", "painter"}).find("$.draws[0] draws lines"), std::string::npos);
  Scene behind = lines;
  behind.draws[0].positions_clip[1].w = -1;
  EXPECT_NE(inapplicable(behind, {"clip", "cyrus_beck"}).find("not in front of the eye"), std::string::npos);
  EXPECT_EQ(inapplicable(behind, {"clip", "liang_barsky"}), "");  // clips in homogeneous space
  EXPECT_THROW(render_with(fan, {{"fill", "scanline"}}), NotSupportedError);
}

// --- The methods the registry added to the pipeline ---

// Primitives the clip stage cut (it made one of their vertices).
size_t clipped_primitives(const Scene& scene, const std::vector<MethodChoice>& methods) {
  CpuOptions options;
  options.fma = true;
  options.methods = methods;
  size_t clipped = 0;
  for (const cpu::classic::ClassicPrimitive& p : cpu::classic::prepare_classic_frame(scene, options).primitives)
    clipped += p.clipped;
  return clipped;
}

// On screen the 2-D clippers (after the divide, against the viewport) draw what Liang–Barsky on the
// homogeneous planes draws: same pixels, same depth.
TEST(ClassicClip, TwoDimensionalLineClippersAgreeWithLiangBarskyOnScreen) {
  const Scene lines = method_scene("clip/liang_barsky/clipped_lines");
  const RenderResult homogeneous = render_with(lines, {{"clip", "liang_barsky"}});
  const RenderResult cohen_sutherland = render_with(lines, {{"clip", "cohen_sutherland"}});
  const RenderResult cyrus_beck = render_with(lines, {{"clip", "cyrus_beck"}});
  EXPECT_EQ(owner_differences(cohen_sutherland, homogeneous), 0u);
  EXPECT_EQ(owner_differences(cyrus_beck, homogeneous), 0u);
  EXPECT_EQ(depth_differences(cyrus_beck, homogeneous), 0u);
  EXPECT_EQ(owner_differences(cyrus_beck, cohen_sutherland), 0u);
  EXPECT_EQ(clipped_primitives(lines, {{"clip", "cohen_sutherland"}}),
            clipped_primitives(lines, {{"clip", "liang_barsky"}}));
  EXPECT_GT(clipped_primitives(lines, {{"clip", "cyrus_beck"}}), 0u);
}

// clipped_triangles with every z moved inside 0..w: Weiler–Atherton clips in 2-D only.
Scene triangles_inside_depth_planes() {
  Scene scene = method_scene("clip/sutherland_hodgman/clipped_triangles");
  for (Draw& draw : scene.draws)
    for (glm::vec4& p : draw.positions_clip) p.z = std::clamp(p.z, 0.0f, p.w);
  return scene;
}

TEST(ClassicClip, WeilerAthertonClipsTrianglesToTheViewport) {
  try {
    render_with(method_scene("clip/sutherland_hodgman/clipped_triangles"), {{"clip", "weiler_atherton"}});
    FAIL() << "a vertex beyond the depth clip planes was clipped in 2-D";
  } catch (const NotSupportedError& error) {
    EXPECT_NE(std::string(error.what()).find("outside the depth clip planes 0 <= z <= w (z = -0.5"), std::string::npos)
        << error.what();
  }
  const Scene triangles = triangles_inside_depth_planes();
  const RenderResult exact = render_with(triangles, {});
  const RenderResult weiler_atherton = render_with(triangles, {{"clip", "weiler_atherton"}});
  EXPECT_GT(clipped_primitives(triangles, {{"clip", "weiler_atherton"}}), 0u);
  EXPECT_EQ(owner_differences(weiler_atherton, exact), 0u);
  EXPECT_EQ(depth_differences(weiler_atherton, exact), 0u);
}

TEST(ClassicFill, FloodFillCoversTheOutlineAndItsInside) {
  const Scene quad = method_scene("fill/scanline/shifted_quad");
  const RenderResult exact = render_with(quad, {});
  const RenderResult flood = render_with(quad, {{"fill", "flood"}});
  EXPECT_EQ(owner_differences(flood, exact), 33u);
  size_t covered_exact = 0, covered_flood = 0;
  for (size_t i = 0; i < exact.owner.size(); ++i) {
    covered_exact += exact.owner[i] != kOwnerBackground;
    covered_flood += flood.owner[i] != kOwnerBackground;
  }
  EXPECT_EQ(covered_flood, 289u);  // the Bresenham outline reaches past the exact edges
  EXPECT_EQ(covered_exact, 256u);
}

// Two quads of constant eye distance w, the farther drawn first, depth compare less: with the
// notes' far 7500, D16 cannot tell w = 5000 from w = 5001 (0.07 of a step), X8_D24 can (17 steps).
Scene pseudo_depth_pair(const std::string& format) {
  const std::string quad_at =
      R"([[1, 1, 0.5, W], [15, 1, 0.5, W], [1, 15, 0.5, W], [15, 1, 0.5, W], [15, 15, 0.5, W], [1, 15, 0.5, W]])";
  const auto at = [&](const char* w) { return std::regex_replace(quad_at, std::regex("W"), w); };
  return parse_scene(
      R"({"name": "pseudo_depth_pair", "width": 16, "height": 16, "space": "pixels", "depth_format": ")" + format +
          R"(", "draws": [{"positions": )" + at("5001") + R"(}, {"positions": )" + at("5000") + "}]}",
      "pseudo_depth_pair");
}

TEST(ClassicDepth, PseudoDepthAtFar7500LosesTheNearerQuadInD16) {
  for (const char* format : {"d16_unorm", "x8_d24_unorm"}) {
    const Scene pair = pseudo_depth_pair(format);
    const RenderResult r = render_with(pair, {{"depth", "pseudo_depth_7500"}});
    size_t nearer = 0, covered = 0;
    for (uint32_t owner : r.owner) {
      covered += owner != kOwnerBackground;
      nearer += owner == encode_owner(1, 0) || owner == encode_owner(1, 1);
    }
    EXPECT_EQ(covered, 196u) << format;
    EXPECT_EQ(nearer, std::string(format) == "d16_unorm" ? 0u : 196u) << format;
  }
  EXPECT_NE(inapplicable(pseudo_depth_pair("d16_unorm"), {"depth", "pseudo_depth_750"}).find("far 750"),
            std::string::npos);
  EXPECT_NEAR(cpu::classic::pseudo_depth_step_at_far(7500, 16), 34.2, 0.05);
  EXPECT_NEAR(cpu::classic::pseudo_depth_step_at_far(75, 16), 0.00229, 0.00001);
}

// --- explain with classic methods (cpu_raster/classic/classic_explain.hpp) ---

// "classic result: owner draw D primitive P" (or background) from the explanation.
uint32_t explained_owner(const std::string& text) {
  std::smatch m;
  if (std::regex_search(text, m, std::regex("classic result: owner draw (\\d+) primitive (\\d+)")))
    return encode_owner(uint32_t(std::stoul(m[1])), uint32_t(std::stoul(m[2])));
  EXPECT_NE(text.find("classic result: owner background"), std::string::npos) << text;
  return kOwnerBackground;
}

TEST(ClassicExplain, TheHistoryEndsWithWhatTheRenderHolds) {
  const std::vector<std::pair<const char*, std::vector<MethodChoice>>> cases{
      {"visibility/painter/cyclic_sticks", {{"visibility", "painter"}}},
      {"visibility/bsp/interpenetrating", {{"visibility", "bsp"}}},
      {"fill/scanline/fan", {{"fill", "flood"}}},
      {"fill/float_edge/shared_edge_quad", {{"fill", "float_edge"}}},
      {"line/bresenham/crossing_framebuffer", {{"line", "bresenham"}, {"clip", "cohen_sutherland"}}},
      {"", {{"clip", "weiler_atherton"}}},  // triangles_inside_depth_planes()
      {"depth/no_fma/steep_plane", {{"depth", "no_fma"}}},
      {"cull/normal_dot_view/flipped_viewport", {{"cull", "normal_dot_view"}}}};
  for (const auto& [relative, methods] : cases) {
    const Scene scene = *relative ? method_scene(relative) : triangles_inside_depth_planes();
    CpuOptions options;
    options.fma = true;
    options.methods = methods;
    const RenderResult rendered = render_classic(scene, options);
    size_t checked = 0;
    for (uint32_t y = 1; y < scene.height; y += 5)
      for (uint32_t x = 2; x < scene.width; x += 5, ++checked) {
        const std::string text = explain_classic_pixel(scene, options, x, y);
        ASSERT_EQ(explained_owner(text), rendered.owner[rendered.index(x, y, 0)])
            << relative << " " << x << "," << y << "\n"
            << text;
        if (rendered.has_depth()) {
          ASSERT_NE(text.find(fmt::format("depth raw {:#x}", rendered.depth_raw[rendered.index(x, y, 0)])),
                    std::string::npos)
              << relative << " " << x << "," << y << "\n"
              << text;
        }
      }
    EXPECT_GT(checked, 30u);
  }
}

TEST(ClassicExplain, NamesTheMethodsDecision) {
  CpuOptions options;
  options.fma = true;
  options.methods = {{"visibility", "painter"}};
  const Scene sticks = method_scene("visibility/painter/cyclic_sticks");
  const RenderResult sticks_render = render_classic(sticks, options);
  size_t covered = 0;
  while (sticks_render.owner[covered] == kOwnerBackground) ++covered;
  const std::string painted =
      explain_classic_pixel(sticks, options, uint32_t(covered % sticks.width), uint32_t(covered / sticks.width));
  EXPECT_NE(painted.find("visibility=painter: painted as fragment"), std::string::npos) << painted;
  options.methods = {{"fill", "flood"}};
  const std::string flood = explain_classic_pixel(method_scene("fill/scanline/fan"), options, 16, 16);
  EXPECT_NE(flood.find("fill=flood: row 16 spans"), std::string::npos) << flood;
  EXPECT_NE(flood.find(", seed ("), std::string::npos) << flood;
  options.methods = {{"line", "dda"}};
  const Scene lines = method_scene("line/dda/inside_endpoints");
  const RenderResult dda_render = render_classic(lines, options);
  size_t on_line = 0;
  while (dda_render.owner[on_line] == kOwnerBackground) ++on_line;
  const std::string dda =
      explain_classic_pixel(lines, options, uint32_t(on_line % lines.width), uint32_t(on_line / lines.width));
  EXPECT_NE(dda.find("line=dda: pixels from ("), std::string::npos) << dda;
  options.methods = {{"depth", "no_fma"}};
  const std::string plane = explain_classic_pixel(method_scene("depth/no_fma/steep_plane"), options, 16, 16);
  EXPECT_NE(plane.find("depth (no_fma plane): z "), std::string::npos) << plane;
  EXPECT_THROW(explain_classic_pixel(sticks, options, sticks.width, 0), UsageError);
}

}  // namespace
}  // namespace rastercmp
