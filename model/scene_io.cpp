// Scene file → Scene (docs/scene-format.md). Top level: framebuffer, viewport, scissor, camera,
// space, defaults, methods and the draws array; draws themselves: model/scene_io_draw.cpp.
#include "model/scene_io.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "model/camera.hpp"
#include "model/depth_format.hpp"
#include "model/errors.hpp"
#include "model/file_read.hpp"
#include "model/scene_io_draw.hpp"
#include "model/scene_json.hpp"

namespace rastercmp {

using scene_io_detail::PositionContext;
using scene_io_detail::PositionSpace;
using scene_json::Node;

namespace {

// viewportBoundsRange = [-32768, 32768], maxViewportDimensions = 16384 (docs/lavapipe-rules.md §0).
constexpr double kViewportBound = 32768;
constexpr double kMaxViewportSide = 16384;
// Owner ids and raw depth: 4 + 4 bytes per sample; one scene may use at most 1 GiB of them.
constexpr uint64_t kBytesPerSample = 8;
constexpr uint64_t kFramebufferBudgetBytes = uint64_t(1) << 30;
constexpr int64_t kInt32Max = std::numeric_limits<int32_t>::max();

// ^[a-z0-9_]+(\.[a-z0-9_]+)*$
bool is_valid_name(std::string_view name) {
  bool segment_empty = true;
  for (const char c : name) {
    if (c == '.') {
      if (segment_empty) return false;
      segment_empty = true;
    } else if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_') {
      segment_empty = false;
    } else {
      return false;
    }
  }
  return !segment_empty;
}

std::string read_name(const Node& root) {
  constexpr const char* kRule = "dotted segments of a-z, 0-9 and _ (^[a-z0-9_]+(\\.[a-z0-9_]+)*$)";
  if (const auto name = root.find("name")) {
    const std::string text = name->as_line("a name string");
    if (!is_valid_name(text)) name->fail(std::string("a name of ") + kRule);
    return text;
  }
  const std::string stem = std::filesystem::path(root.file()).stem().string();
  if (!is_valid_name(stem)) {
    throw InputError(
        root.file(), "$.name",
        fmt::format("expected a \"name\" key, or a file name of {}, found the file name \"{}\"", kRule, stem));
  }
  return stem;
}

void read_framebuffer(const Node& root, Scene& scene) {
  const auto side = [](const Node& node) {
    return uint32_t(node.as_integer(1, kMaxFramebufferSide, "an integer in 1..16384 (maxFramebufferWidth/Height)"));
  };
  if (const auto width = root.find("width")) scene.width = side(*width);
  if (const auto height = root.find("height")) scene.height = side(*height);
  if (const auto samples = root.find("samples")) {
    // framebufferDepthSampleCounts = 1|4 (docs/lavapipe-rules.md §0).
    scene.samples = uint32_t(samples->as_integer(1, 4, "a sample count of 1 or 4"));
    if (scene.samples != 1 && scene.samples != 4) samples->fail("a sample count of 1 or 4");
  }
  if (const auto format = root.find("depth_format")) {
    // The names come from the depth-format table (model/depth_format.hpp), "none" last.
    static constexpr auto kNames = [] {
      std::array<DepthFormat, kAllDepthFormats.size()> names{};
      for (size_t i = 0; i < kDepthFormats.size(); ++i) names[i] = kDepthFormats[i];
      names.back() = DepthFormat::None;
      return names;
    }();
    scene.depth_format = format->as_enum(kNames);
  }
  if (const auto clear = root.find("depth_clear")) {
    scene.depth_clear = float(clear->as_number(0, 1, "a depth clear value in 0..1"));
  }
  const uint64_t bytes = uint64_t(scene.width) * scene.height * scene.samples * kBytesPerSample;
  if (bytes > kFramebufferBudgetBytes) {
    root.fail_message(
        fmt::format("expected width * height * samples * 8 bytes <= 1 GiB (the framebuffer memory budget), found "
                    "{} * {} * {} * 8 = {} bytes ({:.2f} GiB)",
                    scene.width, scene.height, scene.samples, bytes, double(bytes) / double(kFramebufferBudgetBytes)));
  }
}

// Vulkan spec, VkViewport valid usage, with this device's limits.
Viewport read_viewport(const Node& node, const Scene& scene) {
  node.expect_object("a viewport object", {"x", "y", "width", "height", "min_depth", "max_depth"});
  Viewport viewport{0, 0, float(scene.width), float(scene.height), 0, 1};
  const auto bound = [](const Node& n) {
    return float(n.as_number(-kViewportBound, kViewportBound, "a number in -32768..32768 (viewportBoundsRange)"));
  };
  if (const auto x = node.find("x")) viewport.x = bound(*x);
  if (const auto y = node.find("y")) viewport.y = bound(*y);
  if (const auto width = node.find("width")) {
    viewport.width = width->as_float("a width in (0, 16384] (maxViewportDimensions)");
    if (!(viewport.width > 0 && viewport.width <= kMaxViewportSide)) {
      width->fail("a width in (0, 16384] (maxViewportDimensions)");
    }
  }
  if (const auto height = node.find("height")) {
    viewport.height = height->as_float("a height with 0 < |height| <= 16384 (maxViewportDimensions)");
    if (!(viewport.height != 0 && std::fabs(viewport.height) <= kMaxViewportSide)) {
      height->fail("a height with 0 < |height| <= 16384 (maxViewportDimensions)");
    }
  }
  // Without VK_EXT_depth_range_unrestricted both depths lie in 0..1.
  const auto depth = [](const Node& n) { return float(n.as_number(0, 1, "a depth in 0..1")); };
  if (const auto min_depth = node.find("min_depth")) viewport.min_depth = depth(*min_depth);
  if (const auto max_depth = node.find("max_depth")) viewport.max_depth = depth(*max_depth);
  const double x_end = double(viewport.x) + viewport.width;
  const double y_end = double(viewport.y) + viewport.height;
  if (x_end > kViewportBound || y_end < -kViewportBound || y_end > kViewportBound) {
    node.fail_message(
        fmt::format("expected x + width and y + height in -32768..32768 (viewportBoundsRange), found x + width = {}, "
                    "y + height = {}",
                    x_end, y_end));
  }
  return viewport;
}

// VkRect2D of a scissor: offsets >= 0 and offset + extent within int32.
Rect2D read_scissor(const Node& node, const Scene& scene) {
  node.expect_object("a scissor object", {"x", "y", "width", "height"});
  Rect2D scissor{0, 0, scene.width, scene.height};
  const auto offset = [](const Node& n) { return int32_t(n.as_integer(0, kInt32Max, "an integer >= 0")); };
  const auto extent = [](const Node& n) { return uint32_t(n.as_integer(0, kInt32Max, "an integer >= 0")); };
  if (const auto x = node.find("x")) scissor.x = offset(*x);
  if (const auto y = node.find("y")) scissor.y = offset(*y);
  if (const auto width = node.find("width")) scissor.width = extent(*width);
  if (const auto height = node.find("height")) scissor.height = extent(*height);
  if (int64_t(scissor.x) + scissor.width > kInt32Max || int64_t(scissor.y) + scissor.height > kInt32Max) {
    node.fail_message(fmt::format("expected x + width and y + height <= 2147483647, found {} and {}",
                                  int64_t(scissor.x) + scissor.width, int64_t(scissor.y) + scissor.height));
  }
  return scissor;
}

}  // namespace

namespace {

glm::vec3 read_vec3(const Node& node) {
  node.expect_array(3, 3, "3 numbers [x, y, z]");
  glm::vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = node.element(size_t(i)).as_float("a finite number");
  return v;
}

Camera read_camera(const Node& node) {
  node.expect_object("a camera object", {"eye", "target", "up", "fov_y", "near", "far"});
  Camera camera;
  if (const auto eye = node.find("eye")) camera.eye = read_vec3(*eye);
  if (const auto target = node.find("target")) camera.target = read_vec3(*target);
  if (const auto up = node.find("up")) camera.up = read_vec3(*up);
  if (const auto fov = node.find("fov_y")) {
    camera.fov_y_degrees = fov->as_float("a vertical field of view in degrees, 0 < fov_y < 180");
    if (!(camera.fov_y_degrees > 0 && camera.fov_y_degrees < 180)) {
      fov->fail("a vertical field of view in degrees, 0 < fov_y < 180");
    }
  }
  if (const auto near_node = node.find("near")) {
    camera.near_plane = near_node->as_float("a near plane distance > 0");
    if (!(camera.near_plane > 0)) near_node->fail("a near plane distance > 0");
  }
  if (const auto far_node = node.find("far")) {
    const std::string what = fmt::format("a far plane distance > near ({})", camera.near_plane);
    camera.far_plane = far_node->as_float(what);
    if (!(camera.far_plane > camera.near_plane)) far_node->fail(what);
  } else if (!(camera.far_plane > camera.near_plane)) {
    node.fail_message(
        fmt::format("expected near < far (far defaults to {}), found near = {}", camera.far_plane, camera.near_plane));
  }
  if (camera.eye == camera.target) {
    throw InputError(node.file(), node.path() + ".target",
                     "expected a target different from the eye, found the same point");
  }
  if (camera_up_is_degenerate(camera)) {
    throw InputError(node.file(), node.path() + ".up",
                     "expected an up vector that is not zero or parallel to the view direction (target - eye), found "
                     "one that is");
  }
  return camera;
}

// "space" and "camera" decide what positions mean; a camera that would be ignored is an error.
PositionContext read_position_context(const Node& root, Scene& scene) {
  PositionContext context;
  if (const auto camera = root.find("camera")) scene.camera = read_camera(*camera);
  context.space = scene.camera ? PositionSpace::World : PositionSpace::Clip;
  const auto space = root.find("space");
  if (space) {
    const std::string name = space->json().is_string() ? space->json().get<std::string>() : "";
    if (name == "clip")
      context.space = PositionSpace::Clip;
    else if (name == "pixels")
      context.space = PositionSpace::Pixels;
    else if (name == "world")
      context.space = PositionSpace::World;
    else
      space->fail("one of \"clip\", \"pixels\", \"world\"");
  }
  if (context.space == PositionSpace::World && !scene.camera) {
    space->fail("\"clip\" or \"pixels\" (space \"world\" needs a \"camera\")");
  }
  if (context.space != PositionSpace::World && scene.camera) {
    root.find("camera")->fail_message("expected no camera unless space is \"world\" (it would be ignored), found one");
  }
  const Viewport viewport = scene.effective_viewport();
  context.viewport = viewport;
  if (context.space == PositionSpace::Pixels && viewport.max_depth == viewport.min_depth) {
    space->fail_message(
        "expected a viewport with max_depth != min_depth for space \"pixels\" (z maps through "
        "max_depth - min_depth), found equal depths");
  }
  if (context.space == PositionSpace::World) {
    context.world_to_clip = camera_world_to_clip(*scene.camera, viewport.width / std::fabs(viewport.height));
  }
  if (const auto allow = root.find("allow_non_finite")) context.allow_non_finite = allow->as_bool();
  return context;
}

std::vector<MethodChoice> read_methods(const Node& node) {
  if (!node.json().is_object()) node.fail("an object {\"stage\": \"method name\"}");
  std::vector<MethodChoice> methods;
  for (const auto& [stage, name] : node.json().items()) {
    const Node choice(name, scene_json::key_path(node.path(), stage), node.file());
    if (!is_valid_name(stage) || stage.find('.') != std::string::npos) {
      choice.fail_message(fmt::format("expected a stage name of a-z, 0-9 and _, found \"{}\"", stage));
    }
    const std::string method = choice.as_line("a method name string");
    if (method.empty() || !is_valid_name(method) || method.find('.') != std::string::npos) {
      choice.fail("a method name of a-z, 0-9 and _");
    }
    methods.push_back(MethodChoice{stage, method});
  }
  return methods;
}

std::vector<Draw> read_draws(const Node& root, const RasterState& defaults, const PositionContext& context) {
  const auto draws = root.find("draws");
  if (!draws) root.fail_message("expected the required key \"draws\" (an array of 1..255 draw objects), found none");
  const size_t count = draws->expect_array(1, kMaxDraws, "an array of 1..255 draw objects");
  std::vector<Draw> result;
  result.reserve(count);
  for (size_t i = 0; i < count; ++i) result.push_back(scene_io_detail::read_draw(draws->element(i), defaults, context));
  return result;
}

// Reads at most kMaxSceneFileBytes + 1 bytes: a larger file, or an endless one (/dev/zero, a
// pipe), is refused before parsing whatever its reported size.
std::string read_file_text(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(path, "$", "expected a scene file, found a directory");
  }
  const auto too_large = [&path] {
    return InputError(path, "$",
                      fmt::format("expected a scene file of at most {} MiB, found more", kMaxSceneFileBytes >> 20));
  };
  if (std::filesystem::is_regular_file(path, error) && std::filesystem::file_size(path, error) > kMaxSceneFileBytes)
    throw too_large();  // a regular file's size is believed when it is too large; any file is read with the cap
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "$", fmt::format("expected a readable scene file, found: {}", std::strerror(errno)));
  std::string text = read_at_most(in, kMaxSceneFileBytes);  // model/file_read.hpp
  if (in.bad()) {
    throw InputError(path, "$",
                     fmt::format("expected a readable scene file, found a read error: {}", std::strerror(errno)));
  }
  if (text.size() > kMaxSceneFileBytes) throw too_large();
  return text;
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& file) {
  const scene_json::Json document = scene_json::parse_text(text, file);
  const Node root(document, "$", file);
  root.expect_object("a JSON object (the scene)",
                     {"name", "description", "width", "height", "depth_format", "depth_clear", "samples", "viewport",
                      "scissor", "space", "camera", "defaults", "methods", "draws", "allow_non_finite"});
  Scene scene;
  scene.source_path = file;
  scene.name = read_name(root);
  if (const auto description = root.find("description")) scene.description = description->as_line("a one-line string");
  read_framebuffer(root, scene);
  if (const auto viewport = root.find("viewport")) scene.viewport = read_viewport(*viewport, scene);
  if (const auto scissor = root.find("scissor")) scene.scissor = read_scissor(*scissor, scene);
  const PositionContext context = read_position_context(root, scene);
  const auto defaults = root.find("defaults");
  const RasterState state = defaults ? scene_io_detail::read_defaults(*defaults) : RasterState{};
  if (const auto methods = root.find("methods")) scene.methods = read_methods(*methods);
  scene.draws = read_draws(root, state, context);
  return scene;
}

Scene load_scene_file(const std::string& path) { return parse_scene(read_file_text(path), path); }

}  // namespace rastercmp
