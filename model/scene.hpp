// The scene model both renderers share: plain structs, API-neutral.
// A scene states only what differs from the defaults below (docs/scene-format.md).
// Positions reach the renderers in clip space; a camera, when present, is applied
// once on the host (model/camera.cpp) so both renderers start from the same bits
// (docs/lavapipe-rules.md §1.7).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace rastercmp {

enum class DepthFormat { None, D16Unorm, X8D24Unorm, D32Sfloat };
enum class Topology { PointList, LineList, LineStrip, TriangleList, TriangleStrip, TriangleFan };
enum class CullMode { None, Front, Back, FrontAndBack };
enum class FrontFace { CounterClockwise, Clockwise };
enum class PolygonMode { Fill, Line, Point };
enum class LineMode { Default, Rectangular, Bresenham, RectangularSmooth };
enum class CompareOp { Never, Less, Equal, LessOrEqual, Greater, NotEqual, GreaterOrEqual, Always };

// Largest framebuffer side lavapipe accepts (maxFramebufferWidth/Height).
inline constexpr uint32_t kMaxFramebufferSide = 16384;
// Owner ids pack the draw index into the top 8 bits and the primitive index into the low 24.
inline constexpr uint32_t kMaxDraws = 255;
inline constexpr uint32_t kMaxPrimitivesPerDraw = 1u << 24;

struct Viewport {
  float x = 0, y = 0, width = 0, height = 0;
  float min_depth = 0, max_depth = 1;
};

struct Rect2D {
  int32_t x = 0, y = 0;
  uint32_t width = 0, height = 0;
};

// Right-handed look-at camera with Vulkan's 0..1 clip depth (GLM_FORCE_DEPTH_ZERO_TO_ONE).
struct Camera {
  glm::vec3 eye{0, 0, 1};
  glm::vec3 target{0, 0, 0};
  glm::vec3 up{0, 1, 0};
  float fov_y_degrees = 60;
  float near_plane = 0.1f;
  float far_plane = 100;
};

struct DepthBias {
  bool enable = false;
  float constant_factor = 0;
  float slope_factor = 0;
  float clamp = 0;
};

struct DepthState {
  bool test_enable = true;
  bool write_enable = true;
  CompareOp compare_op = CompareOp::Less;
};

struct RasterState {
  CullMode cull_mode = CullMode::None;
  FrontFace front_face = FrontFace::CounterClockwise;
  PolygonMode polygon_mode = PolygonMode::Fill;
  LineMode line_mode = LineMode::Default;
  float line_width = 1;
  DepthState depth;
  DepthBias depth_bias;
  bool depth_clamp = false;
  // Absent: VK_EXT_depth_clip_enable is not chained and depth clip is !depth_clamp.
  std::optional<bool> depth_clip;

  bool depth_clip_enabled() const { return depth_clip.value_or(!depth_clamp); }
};

struct Draw {
  std::string name;  // optional label, for reports
  Topology topology = Topology::TriangleList;
  std::vector<glm::vec4> positions_clip;  // after the camera, if any
  std::vector<uint32_t> indices;          // empty: non-indexed
  RasterState state;

  uint32_t vertex_count() const {
    return static_cast<uint32_t>(indices.empty() ? positions_clip.size() : indices.size());
  }
};

// Per-method overrides chosen with --method STAGE=NAME or a scene's "methods" object.
// Empty means the exact pipeline's own choice.
struct MethodChoice {
  std::string stage;
  std::string name;
};

struct Scene {
  std::string name;         // dotted case id, e.g. rastercmp.fill.top_left.shared_edge
  std::string description;  // one line for reports
  std::string source_path;  // file it was loaded from, for messages
  uint32_t width = 64;
  uint32_t height = 64;
  DepthFormat depth_format = DepthFormat::D32Sfloat;
  float depth_clear = 1.0f;
  uint32_t samples = 1;
  std::optional<Viewport> viewport;  // absent: the whole framebuffer, depth 0..1
  std::optional<Rect2D> scissor;     // absent: the whole framebuffer
  std::optional<Camera> camera;
  std::vector<MethodChoice> methods;
  std::vector<Draw> draws;

  Viewport effective_viewport() const { return viewport.value_or(Viewport{0, 0, float(width), float(height), 0, 1}); }
  Rect2D effective_scissor() const { return scissor.value_or(Rect2D{0, 0, width, height}); }
  bool has_depth() const { return depth_format != DepthFormat::None; }
};

const char* to_string(DepthFormat);
const char* to_string(Topology);
const char* to_string(CullMode);
const char* to_string(FrontFace);
const char* to_string(PolygonMode);
const char* to_string(LineMode);
const char* to_string(CompareOp);

bool is_triangle_topology(Topology);
bool is_line_topology(Topology);

// Bits of the stored depth value (16, 24 or 32; 0 for None).
uint32_t depth_bits(DepthFormat);

}  // namespace rastercmp
