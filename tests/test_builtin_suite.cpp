// The built-in conformance suite (scenes/**/*.json, docs/suite.md): every scene loads, its name
// matches its path, it restates no default, and the suite as a whole covers the list of
// features listed in docs/suite.md. Coverage is judged from the loaded scenes (clip-space
// positions, state), not from file names, so a scene that stops testing what it claims fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <nlohmann/json.hpp>

#include "model/errors.hpp"
#include "model/scene.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

const fs::path kSourceDir = fs::path(RASTERCMP_SOURCE_DIR);
const fs::path kScenesDir = kSourceDir / "scenes";
// scenes/methods/: the classic-method scenes, owned and checked by tests/test_classic_scenes.cpp and
// documented in docs/methods.md. Here they only have to load, match their paths and keep names unique.
const std::string kMethodScenesPrefix = "methods/";
constexpr size_t kMinScenes = 44;
constexpr uint32_t kSmallSide = 256;  // every framebuffer side but the far-from-origin scene's

struct SuiteScene {
  std::string relative_path;  // e.g. fill/top_left/shared_edge.json
  Scene scene;
  Json raw;
};

struct Suite {
  std::vector<SuiteScene> scenes;         // the built-in suite
  std::vector<SuiteScene> method_scenes;  // scenes/methods/
  std::vector<std::string> load_errors;

  std::vector<const SuiteScene*> everything() const {
    std::vector<const SuiteScene*> all;
    for (const SuiteScene& entry : scenes) all.push_back(&entry);
    for (const SuiteScene& entry : method_scenes) all.push_back(&entry);
    return all;
  }
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Loads every scenes/**/*.json once, in path order.
const Suite& suite() {
  static const Suite loaded = [] {
    Suite result;
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(kScenesDir)) {
      if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      const std::string relative = fs::relative(file, kScenesDir).generic_string();
      try {
        const bool method_scene = relative.rfind(kMethodScenesPrefix, 0) == 0;
        (method_scene ? result.method_scenes : result.scenes)
            .push_back({relative, load_scene_file(file.string()), Json::parse(read_text(file))});
      } catch (const std::exception& error) {
        result.load_errors.push_back(relative + ": " + error.what());
      }
    }
    return result;
  }();
  return loaded;
}

// fill/top_left/shared_edge.json → rastercmp.fill.top_left.shared_edge
std::string name_for_path(std::string relative) {
  relative.resize(relative.size() - std::string(".json").size());
  for (char& c : relative) c = c == '/' ? '.' : c;
  return "rastercmp." + relative;
}

const Scene* find_scene(const std::string& name) {
  for (const SuiteScene& entry : suite().scenes) {
    if (entry.scene.name == name) return &entry.scene;
  }
  return nullptr;
}

// --- geometry of the loaded scenes -----------------------------------------------------------

using Triangle = std::array<glm::vec4, 3>;
using Segment = std::array<glm::vec4, 2>;

std::vector<glm::vec4> vertices_in_order(const Draw& draw) {
  if (draw.indices.empty()) return draw.positions_clip;
  std::vector<glm::vec4> vertices;
  for (const uint32_t index : draw.indices) vertices.push_back(draw.positions_clip[index]);
  return vertices;
}

// Vulkan spec "Primitive Topologies" (winding is not needed here, so strips are not reordered).
std::vector<Triangle> triangles_of(const Draw& draw) {
  const std::vector<glm::vec4> v = vertices_in_order(draw);
  std::vector<Triangle> result;
  if (draw.topology == Topology::TriangleList) {
    for (size_t i = 0; i + 2 < v.size(); i += 3) result.push_back({v[i], v[i + 1], v[i + 2]});
  } else if (draw.topology == Topology::TriangleStrip) {
    for (size_t i = 0; i + 2 < v.size(); ++i) result.push_back({v[i], v[i + 1], v[i + 2]});
  } else if (draw.topology == Topology::TriangleFan) {
    for (size_t i = 1; i + 1 < v.size(); ++i) result.push_back({v[0], v[i], v[i + 1]});
  }
  return result;
}

std::vector<Segment> segments_of(const Draw& draw) {
  const std::vector<glm::vec4> v = vertices_in_order(draw);
  std::vector<Segment> result;
  const size_t step = draw.topology == Topology::LineList ? 2 : 1;
  if (is_line_topology(draw.topology)) {
    for (size_t i = 0; i + 1 < v.size(); i += step) result.push_back({v[i], v[i + 1]});
  }
  return result;
}

bool in_front_of_eye(const glm::vec4& pos_clip) { return pos_clip.w > 0; }

// Window x, y of a vertex with w > 0 (Vulkan spec "Controlling the Viewport"), in double.
glm::dvec2 window_xy(const Scene& scene, const glm::vec4& pos_clip) {
  const Viewport viewport = scene.effective_viewport();
  const double x_ndc = double(pos_clip.x) / pos_clip.w, y_ndc = double(pos_clip.y) / pos_clip.w;
  return {viewport.x + 0.5 * viewport.width * (x_ndc + 1), viewport.y + 0.5 * viewport.height * (y_ndc + 1)};
}

bool inside_clip_volume(const glm::vec4& p) {
  return p.w > 0 && std::fabs(p.x) <= p.w && std::fabs(p.y) <= p.w && p.z >= 0 && p.z <= p.w;
}

bool fully_inside(const Triangle& t) {
  return inside_clip_volume(t[0]) && inside_clip_volume(t[1]) && inside_clip_volume(t[2]);
}

// Window-space area in square pixels; only meaningful for a triangle inside the clip volume.
double window_area(const Scene& scene, const Triangle& t) {
  const glm::dvec2 a = window_xy(scene, t[0]), b = window_xy(scene, t[1]), c = window_xy(scene, t[2]);
  return 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

double longest_edge(const Scene& scene, const Triangle& t) {
  double longest = 0;
  for (int i = 0; i < 3; ++i) {
    const glm::dvec2 d = window_xy(scene, t[i]) - window_xy(scene, t[(i + 1) % 3]);
    longest = std::max(longest, std::hypot(d.x, d.y));
  }
  return longest;
}

bool on_pixel_centre(double window_coordinate) { return window_coordinate - std::floor(window_coordinate) == 0.5; }

// All three vertices on pixel centres and one edge horizontal or vertical through them.
bool tie_triangle(const Scene& scene, const Triangle& t) {
  if (!fully_inside(t)) return false;
  std::array<glm::dvec2, 3> w{window_xy(scene, t[0]), window_xy(scene, t[1]), window_xy(scene, t[2])};
  for (const glm::dvec2& p : w) {
    if (!on_pixel_centre(p.x) || !on_pixel_centre(p.y)) return false;
  }
  for (int i = 0; i < 3; ++i) {
    const glm::dvec2& a = w[size_t(i)];
    const glm::dvec2& b = w[size_t((i + 1) % 3)];
    if (a.x == b.x || a.y == b.y) return true;
  }
  return false;
}

bool same_vertex(const glm::vec4& a, const glm::vec4& b) { return a == b; }

bool shares_edge(const Triangle& a, const Triangle& b) {
  int shared = 0;
  for (const glm::vec4& p : a) {
    for (const glm::vec4& q : b) shared += same_vertex(p, q) ? 1 : 0;
  }
  return shared == 2;
}

bool zero_area(const Triangle& t) {
  if (same_vertex(t[0], t[1]) || same_vertex(t[1], t[2]) || same_vertex(t[0], t[2])) return true;
  const glm::dvec2 a{t[0].x / double(t[0].w), t[0].y / double(t[0].w)};
  const glm::dvec2 b{t[1].x / double(t[1].w), t[1].y / double(t[1].w)};
  const glm::dvec2 c{t[2].x / double(t[2].w), t[2].y / double(t[2].w)};
  return std::fabs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y)) < 1e-9;
}

// --- queries over the whole suite ------------------------------------------------------------

using DrawPredicate = std::function<bool(const Scene&, const Draw&)>;
using TrianglePredicate = std::function<bool(const Scene&, const Triangle&)>;

bool any_draw(const DrawPredicate& predicate) {
  for (const SuiteScene& entry : suite().scenes) {
    for (const Draw& draw : entry.scene.draws) {
      if (predicate(entry.scene, draw)) return true;
    }
  }
  return false;
}

bool any_triangle(const TrianglePredicate& predicate) {
  return any_draw([&](const Scene& scene, const Draw& draw) {
    for (const Triangle& t : triangles_of(draw)) {
      if (predicate(scene, t)) return true;
    }
    return false;
  });
}

bool any_vertex(const std::function<bool(const glm::vec4&)>& predicate) {
  return any_draw([&](const Scene&, const Draw& draw) {
    return std::any_of(draw.positions_clip.begin(), draw.positions_clip.end(), predicate);
  });
}

template <class Value>
std::set<Value> collect(
    const std::function<Value(const Scene&, const Draw&)>& value_of,
    const DrawPredicate& filter = [](const Scene&, const Draw&) { return true; }) {
  std::set<Value> values;
  any_draw([&](const Scene& scene, const Draw& draw) {
    if (filter(scene, draw)) values.insert(value_of(scene, draw));
    return false;
  });
  return values;
}

bool uses_unsupported_feature(const Draw& draw) {
  return draw.state.polygon_mode != PolygonMode::Fill || draw.state.line_mode == LineMode::RectangularSmooth ||
         draw.topology == Topology::PointList;
}

bool is_triangles(const Scene&, const Draw& draw) { return is_triangle_topology(draw.topology); }
bool is_lines(const Scene&, const Draw& draw) { return is_line_topology(draw.topology); }

// --- structure --------------------------------------------------------------------------------

TEST(BuiltinSuite, EverySceneLoads) {
  for (const std::string& error : suite().load_errors) ADD_FAILURE() << error;
  EXPECT_GE(suite().scenes.size(), kMinScenes) << "scenes found under " << kScenesDir;
}

TEST(BuiltinSuite, NamesMatchFilePathsAndAreUnique) {
  std::set<std::string> names;
  for (const SuiteScene* entry : suite().everything()) {
    EXPECT_EQ(entry->scene.name, name_for_path(entry->relative_path)) << entry->relative_path;
    EXPECT_TRUE(entry->raw.contains("name")) << entry->relative_path << " states its name explicitly";
    EXPECT_TRUE(names.insert(entry->scene.name).second) << "duplicate name " << entry->scene.name;
  }
}

TEST(BuiltinSuite, EverySceneHasADescription) {
  for (const SuiteScene& entry : suite().scenes) {
    EXPECT_GE(entry.scene.description.size(), 30u) << entry.scene.name << ": one line saying what it checks";
  }
}

// Documented defaults (docs/scene-format.md) that a scene file must not restate.
const Json kDrawDefaults = {{"topology", "triangle_list"}, {"cull", "none"},         {"front_face", "ccw"},
                            {"polygon_mode", "fill"},      {"line_mode", "default"}, {"line_width", 1},
                            {"depth_test", true},          {"depth_write", true},    {"depth_compare", "less"},
                            {"depth_clamp", false}};

void expect_no_restated_keys(const Json& object, const Json& defaults, const std::string& where) {
  for (const auto& [key, value] : object.items()) {
    if (defaults.contains(key)) {
      EXPECT_NE(value, defaults[key]) << where << "." << key << " restates its default";
    }
  }
}

void expect_bias_not_default(const Json& draw, const std::string& where) {
  if (draw.contains("depth_bias")) {
    expect_no_restated_keys(draw["depth_bias"], {{"constant", 0}, {"slope", 0}, {"clamp", 0}, {"enable", true}},
                            where + ".depth_bias");
  }
}

TEST(BuiltinSuite, ScenesStateOnlyWhatDiffersFromDefaults) {
  for (const SuiteScene& entry : suite().scenes) {
    const Json& raw = entry.raw;
    const Scene& scene = entry.scene;
    const std::string& where = scene.name;
    expect_no_restated_keys(raw,
                            {{"width", 64},
                             {"height", 64},
                             {"depth_format", "d32_sfloat"},
                             {"depth_clear", 1},
                             {"samples", 1},
                             {"space", scene.camera ? "world" : "clip"},
                             {"allow_non_finite", false}},
                            where);
    const Json default_camera = {{"eye", {0, 0, 1}}, {"target", {0, 0, 0}}, {"up", {0, 1, 0}},
                                 {"fov_y", 60},      {"near", 0.1},         {"far", 100}};
    if (raw.contains("camera")) expect_no_restated_keys(raw["camera"], default_camera, where + ".camera");
    const Json full_viewport = {{"x", 0},         {"y", 0},        {"width", scene.width}, {"height", scene.height},
                                {"min_depth", 0}, {"max_depth", 1}};
    if (raw.contains("viewport")) expect_no_restated_keys(raw["viewport"], full_viewport, where + ".viewport");
    const Json full_scissor = {{"x", 0}, {"y", 0}, {"width", scene.width}, {"height", scene.height}};
    if (raw.contains("scissor")) expect_no_restated_keys(raw["scissor"], full_scissor, where + ".scissor");
    Json draw_defaults = kDrawDefaults;
    if (raw.contains("defaults")) {
      expect_no_restated_keys(raw["defaults"], kDrawDefaults, where + ".defaults");
      expect_bias_not_default(raw["defaults"], where + ".defaults");
      for (const auto& [key, value] : raw["defaults"].items()) draw_defaults[key] = value;
    }
    for (size_t i = 0; i < raw["draws"].size(); ++i) {
      const std::string draw_where = where + ".draws[" + std::to_string(i) + "]";
      expect_no_restated_keys(raw["draws"][i], draw_defaults, draw_where);
      expect_bias_not_default(raw["draws"][i], draw_where);
    }
  }
}

TEST(BuiltinSuite, FramebuffersAreSmallExceptOne) {
  std::vector<std::string> big;
  for (const SuiteScene& entry : suite().scenes) {
    const Scene& s = entry.scene;
    EXPECT_GE(std::min(s.width, s.height), 16u) << s.name;
    if (std::max(s.width, s.height) > kSmallSide) big.push_back(s.name);
  }
  EXPECT_LE(big.size(), 1u) << "only the far-from-origin scene may exceed " << kSmallSide << " px";
}

TEST(BuiltinSuite, UnsupportedFeaturesOnlyInAtMostTwoNotSupportedScenes) {
  size_t not_supported_scenes = 0;
  for (const SuiteScene& entry : suite().scenes) {
    const Scene& s = entry.scene;
    const bool named = s.name.find("not_supported") != std::string::npos;
    const bool uses = std::any_of(s.draws.begin(), s.draws.end(), uses_unsupported_feature);
    EXPECT_EQ(named, uses) << s.name
                           << (named ? " is named not_supported but uses only supported features"
                                     : " uses polygon_mode line/point, smooth lines or point_list");
    if (named) {
      EXPECT_NE(s.description.find("NotSupported"), std::string::npos) << s.name;
    }
    not_supported_scenes += named ? 1 : 0;
  }
  EXPECT_LE(not_supported_scenes, 2u);
}

TEST(BuiltinSuite, DocsListEverySceneAndNoOther) {
  const std::string docs = read_text(kSourceDir / "docs" / "suite.md");
  for (const SuiteScene& entry : suite().scenes) {
    EXPECT_NE(docs.find("`" + entry.scene.name + "`"), std::string::npos) << entry.scene.name << " in docs/suite.md";
  }
  const std::string row_start = "| `rastercmp.";
  for (size_t at = docs.find(row_start); at != std::string::npos; at = docs.find(row_start, at + 1)) {
    const size_t name_begin = at + 3;
    const std::string name = docs.substr(name_begin, docs.find('`', name_begin) - name_begin);
    EXPECT_NE(find_scene(name), nullptr) << "docs/suite.md lists " << name << ", which is not in scenes/";
  }
}

// --- coverage ---------------------------------------------------------------------------------

TEST(BuiltinSuiteCoverage, FillRuleTiesSharedEdgesFansAndGrids) {
  EXPECT_TRUE(any_triangle(tie_triangle)) << "a triangle with vertices and an axis-aligned edge on pixel centres";
  EXPECT_TRUE(any_draw([](const Scene& scene, const Draw& draw) {
    const std::vector<Triangle> t = triangles_of(draw);
    for (size_t i = 0; i < t.size(); ++i) {
      for (size_t j = i + 1; j < t.size(); ++j) {
        if (tie_triangle(scene, t[i]) && shares_edge(t[i], t[j])) return true;
      }
    }
    return false;
  })) << "two triangles sharing an edge through pixel centres";
  EXPECT_TRUE(any_draw([](const Scene&, const Draw& draw) {
    std::map<std::array<float, 4>, int> uses;
    for (const Triangle& t : triangles_of(draw)) {
      for (const glm::vec4& p : t) ++uses[{p.x, p.y, p.z, p.w}];
    }
    return std::any_of(uses.begin(), uses.end(), [](const auto& use) { return use.second >= 8; });
  })) << "a fan of at least 8 triangles around one shared vertex";
  EXPECT_TRUE(any_draw([](const Scene&, const Draw& draw) {
    return !draw.indices.empty() && triangles_of(draw).size() >= 100;
  })) << "an indexed tessellated grid of at least 100 triangles";
}

TEST(BuiltinSuiteCoverage, SliversTinyAndHugeTriangles) {
  EXPECT_TRUE(any_triangle([](const Scene& scene, const Triangle& t) {
    const double length = longest_edge(scene, t);
    return fully_inside(t) && length >= 64 && 2 * window_area(scene, t) / length < 0.5;
  })) << "a sliver: at least 64 px long and under half a pixel wide";
  EXPECT_TRUE(any_triangle([](const Scene& scene, const Triangle& t) {
    const double area = window_area(scene, t);
    return fully_inside(t) && area > 0 && area < 0.05;
  })) << "a sub-pixel triangle of under 0.05 square pixels";
  EXPECT_TRUE(any_vertex([](const glm::vec4& p) {
    return in_front_of_eye(p) && std::max(std::fabs(p.x), std::fabs(p.y)) > 100 * p.w;
  })) << "a vertex more than 100 viewports outside (clipped in x/y)";
}

TEST(BuiltinSuiteCoverage, FarFromOriginInABigFramebuffer) {
  EXPECT_TRUE(any_triangle([](const Scene& scene, const Triangle& t) {
    if (scene.width < 2048 || scene.height < 1536 || !fully_inside(t)) return false;
    return std::all_of(t.begin(), t.end(), [&](const glm::vec4& p) {
      const glm::dvec2 w = window_xy(scene, p);
      return w.x >= 1536 && w.y >= 1152;
    });
  }));
}

TEST(BuiltinSuiteCoverage, NearFarPlanesBehindTheEyeAndACamera) {
  EXPECT_TRUE(any_vertex([](const glm::vec4& p) { return p.w > 0 && p.z < 0; })) << "a vertex in front of near";
  EXPECT_TRUE(any_vertex([](const glm::vec4& p) { return p.w > 0 && p.z > p.w; })) << "a vertex beyond far";
  EXPECT_TRUE(any_vertex([](const glm::vec4& p) { return p.w < 0; })) << "a vertex behind the eye";
  EXPECT_TRUE(any_draw([](const Scene& scene, const Draw&) { return scene.camera.has_value(); }));
}

TEST(BuiltinSuiteCoverage, CullModesAndFrontFaces) {
  const auto culls = collect<CullMode>([](const Scene&, const Draw& d) { return d.state.cull_mode; }, is_triangles);
  EXPECT_EQ(culls.size(), 4u) << "none, front, back, front_and_back";
  const auto faces =
      collect<FrontFace>([](const Scene&, const Draw& d) { return d.state.front_face; },
                         [](const Scene&, const Draw& d) { return d.state.cull_mode != CullMode::None; });
  EXPECT_EQ(faces.size(), 2u) << "ccw and cw front faces, each with culling on";
}

const std::map<CompareOp, std::string> kCompareScenes = {{CompareOp::Never, "never"},
                                                         {CompareOp::Less, "less"},
                                                         {CompareOp::Equal, "equal"},
                                                         {CompareOp::LessOrEqual, "less_or_equal"},
                                                         {CompareOp::Greater, "greater"},
                                                         {CompareOp::NotEqual, "not_equal"},
                                                         {CompareOp::GreaterOrEqual, "greater_or_equal"},
                                                         {CompareOp::Always, "always"}};

TEST(BuiltinSuiteCoverage, EveryCompareOpHasItsOwnScene) {
  for (const auto& [op, suffix] : kCompareScenes) {
    const Scene* scene = find_scene("rastercmp.depth.compare." + suffix);
    ASSERT_NE(scene, nullptr) << "rastercmp.depth.compare." << suffix;
    ASSERT_GE(scene->draws.size(), 2u) << scene->name << ": two overlapping draws";
    EXPECT_EQ(scene->draws.back().state.depth.compare_op, op) << scene->name;
  }
}

// A later draw with `op` that repeats a triangle of an earlier draw bit for bit (equal depths).
bool has_equal_depth_redraw(const Scene& scene, CompareOp op) {
  for (size_t later = 1; later < scene.draws.size(); ++later) {
    if (scene.draws[later].state.depth.compare_op != op) continue;
    for (size_t earlier = 0; earlier < later; ++earlier) {
      for (const Triangle& a : triangles_of(scene.draws[earlier])) {
        for (const Triangle& b : triangles_of(scene.draws[later])) {
          if (a == b) return true;
        }
      }
    }
  }
  return false;
}

TEST(BuiltinSuiteCoverage, EqualDepthForEqualLessOrEqualAndNotEqual) {
  for (const CompareOp op : {CompareOp::Equal, CompareOp::LessOrEqual, CompareOp::NotEqual}) {
    EXPECT_TRUE(any_draw([&](const Scene& scene, const Draw&) { return has_equal_depth_redraw(scene, op); }))
        << to_string(op);
  }
}

TEST(BuiltinSuiteCoverage, AllDepthFormats) {
  const auto formats = collect<DepthFormat>([](const Scene& s, const Draw&) { return s.depth_format; });
  EXPECT_EQ(formats.size(), 4u) << "d16_unorm, x8_d24_unorm, d32_sfloat and none";
}

TEST(BuiltinSuiteCoverage, DepthBiasVariantsOnEveryFormat) {
  using Check = std::function<bool(const DepthBias&)>;
  const std::map<std::string, Check> variants = {
      {"constant", [](const DepthBias& b) { return b.constant_factor > 0; }},
      {"slope", [](const DepthBias& b) { return b.slope_factor > 0; }},
      {"positive clamp", [](const DepthBias& b) { return b.clamp > 0; }},
      {"negative clamp", [](const DepthBias& b) { return b.clamp < 0; }},
      {"negative factors", [](const DepthBias& b) { return b.constant_factor < 0 && b.slope_factor < 0; }}};
  for (const DepthFormat format : {DepthFormat::D16Unorm, DepthFormat::X8D24Unorm, DepthFormat::D32Sfloat}) {
    for (const auto& variant : variants) {  // not a structured binding: clang 14 cannot capture one
      const std::string& what = variant.first;
      const Check& check = variant.second;
      EXPECT_TRUE(any_draw([&](const Scene& scene, const Draw& draw) {
        return scene.depth_format == format && is_triangle_topology(draw.topology) && draw.state.depth_bias.enable &&
               check(draw.state.depth_bias);
      })) << what
          << " depth bias on " << to_string(format);
    }
  }
}

bool beyond_near_or_far(const Draw& draw) {
  return std::any_of(draw.positions_clip.begin(), draw.positions_clip.end(),
                     [](const glm::vec4& p) { return p.w > 0 && (p.z < 0 || p.z > p.w); });
}

TEST(BuiltinSuiteCoverage, DepthClampAndExplicitDepthClip) {
  for (const bool clamp : {false, true}) {
    EXPECT_TRUE(any_draw([&](const Scene&, const Draw& d) {
      return d.state.depth_clamp == clamp && beyond_near_or_far(d);
    })) << "geometry beyond near/far with depth_clamp "
        << clamp;
  }
  for (const bool clip : {false, true}) {
    EXPECT_TRUE(any_draw([&](const Scene&, const Draw& d) { return d.state.depth_clip == std::optional<bool>(clip); }))
        << "depth_clip explicitly " << clip;
  }
}

TEST(BuiltinSuiteCoverage, ZFightingPairWithAndWithoutPolygonOffset) {
  const Scene* plain = find_scene("rastercmp.depth.zfight.coplanar");
  const Scene* offset = find_scene("rastercmp.depth.zfight.polygon_offset");
  ASSERT_TRUE(plain && offset);
  ASSERT_EQ(plain->draws.size(), offset->draws.size());
  for (size_t i = 0; i < plain->draws.size(); ++i) {
    EXPECT_EQ(plain->draws[i].positions_clip, offset->draws[i].positions_clip) << "draw " << i;
    EXPECT_FALSE(plain->draws[i].state.depth_bias.enable) << "draw " << i;
  }
  EXPECT_TRUE(offset->draws.back().state.depth_bias.enable);
}

TEST(BuiltinSuiteCoverage, TheLectureHouseAtThreeFarPlanes) {
  for (const float far_plane : {75.0f, 750.0f, 7500.0f}) {
    const std::string suffix = "far_" + std::to_string(int(far_plane));
    for (const auto& [name, format] : {std::pair{"rastercmp.house." + suffix, DepthFormat::D16Unorm},
                                       std::pair{"rastercmp.house.d24." + suffix, DepthFormat::X8D24Unorm}}) {
      const Scene* scene = find_scene(name);
      ASSERT_NE(scene, nullptr) << name;
      ASSERT_TRUE(scene->camera.has_value()) << name;
      EXPECT_EQ(scene->camera->near_plane, 25.0f) << name;
      EXPECT_EQ(scene->camera->far_plane, far_plane) << name;
      EXPECT_EQ(scene->depth_format, format) << name;
    }
  }
}

TEST(BuiltinSuiteCoverage, LineTopologiesModesWidthsAndClipping) {
  const auto topologies = collect<Topology>([](const Scene&, const Draw& d) { return d.topology; }, is_lines);
  EXPECT_EQ(topologies, (std::set<Topology>{Topology::LineList, Topology::LineStrip}));
  const auto modes = collect<LineMode>([](const Scene&, const Draw& d) { return d.state.line_mode; }, is_lines);
  for (const LineMode mode : {LineMode::Default, LineMode::Rectangular, LineMode::Bresenham}) {
    EXPECT_TRUE(modes.count(mode)) << to_string(mode);
  }
  const auto widths = collect<float>([](const Scene&, const Draw& d) { return d.state.line_width; }, is_lines);
  for (const float width : {1.0f, 2.5f, 4.0f, 6.0f}) EXPECT_TRUE(widths.count(width)) << "line width " << width;
  EXPECT_TRUE(any_draw([](const Scene&, const Draw& draw) {
    for (const Segment& s : segments_of(draw)) {
      if (inside_clip_volume(s[0]) != inside_clip_volume(s[1])) return true;
    }
    return false;
  })) << "a line with one end inside the clip volume and one outside";
}

TEST(BuiltinSuiteCoverage, MultisamplingWithAScissor) {
  EXPECT_TRUE(
      any_draw([](const Scene& s, const Draw& d) { return s.samples == 4 && is_triangle_topology(d.topology); }));
  EXPECT_TRUE(any_draw([](const Scene& s, const Draw&) { return s.samples == 4 && s.scissor.has_value(); }));
}

TEST(BuiltinSuiteCoverage, DegenerateTrianglesMixedWithNormalOnes) {
  EXPECT_TRUE(any_draw([](const Scene&, const Draw& draw) {
    const std::vector<Triangle> t = triangles_of(draw);
    const auto degenerate = std::count_if(t.begin(), t.end(), zero_area);
    return degenerate >= 3 && size_t(degenerate) < t.size();
  })) << "a draw with at least three zero-area triangles among normal ones";
}

TEST(BuiltinSuiteCoverage, ScissorViewportOffsetAndYFlip) {
  EXPECT_TRUE(any_draw([](const Scene& s, const Draw&) {
    const Rect2D r = s.effective_scissor();
    return r.x > 0 && r.y > 0 && r.x + r.width < s.width && r.y + r.height < s.height;
  })) << "an inner scissor";
  EXPECT_TRUE(any_draw([](const Scene& s, const Draw&) {
    const Viewport v = s.effective_viewport();
    return v.x > 0 && v.y > 0 && v.height > 0 && v.x + v.width < s.width && v.y + v.height < s.height;
  })) << "a viewport smaller than the framebuffer and offset";
  EXPECT_TRUE(any_draw([](const Scene& s, const Draw&) { return s.effective_viewport().height < 0; }))
      << "a negative-height viewport";
}

TEST(BuiltinSuiteCoverage, StripsFansAndIndexedDraws) {
  const auto indexed = collect<Topology>([](const Scene&, const Draw& d) { return d.topology; },
                                         [](const Scene&, const Draw& d) { return !d.indices.empty(); });
  for (const Topology topology : {Topology::TriangleList, Topology::TriangleStrip, Topology::TriangleFan}) {
    EXPECT_TRUE(indexed.count(topology)) << "indexed " << to_string(topology);
    EXPECT_TRUE(any_draw([&](const Scene&, const Draw& d) { return d.topology == topology && d.indices.empty(); }))
        << "non-indexed " << to_string(topology);
  }
}

bool same_state(const RasterState& a, const RasterState& b) {
  return a.cull_mode == b.cull_mode && a.front_face == b.front_face && a.line_mode == b.line_mode &&
         a.line_width == b.line_width && a.depth.test_enable == b.depth.test_enable &&
         a.depth.write_enable == b.depth.write_enable && a.depth.compare_op == b.depth.compare_op &&
         a.depth_bias.enable == b.depth_bias.enable && a.depth_clamp == b.depth_clamp && a.depth_clip == b.depth_clip;
}

TEST(BuiltinSuiteCoverage, MultiDrawScenesWithDifferentState) {
  EXPECT_TRUE(any_draw([](const Scene& scene, const Draw&) {
    std::vector<RasterState> distinct;
    for (const Draw& draw : scene.draws) {
      const bool seen = std::any_of(distinct.begin(), distinct.end(),
                                    [&](const RasterState& s) { return same_state(s, draw.state); });
      if (!seen) distinct.push_back(draw.state);
    }
    return distinct.size() >= 5;
  })) << "a scene whose draws use at least five different states";
  EXPECT_TRUE(any_draw([](const Scene& scene, const Draw&) { return scene.draws.size() == kMaxDraws; }))
      << "a scene with the maximum of " << kMaxDraws << " draws";
}

}  // namespace
}  // namespace rastercmp
