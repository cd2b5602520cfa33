// One draw object: topology, positions (→ clip space), indices, count and state.
#include <cfloat>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "model/camera.hpp"
#include "model/scene_io_draw.hpp"

namespace rastercmp::scene_io_detail {

using scene_json::Json;
using scene_json::Node;

namespace {

constexpr uint64_t kMaxVertices = std::numeric_limits<uint32_t>::max();

// Vertices each topology needs: at least `min` and, for lists, a multiple of `multiple`
// (Vulkan would silently drop the leftover vertices; here they are a mistake in the file).
struct VertexRule {
  uint64_t min;
  uint64_t multiple;
};

VertexRule vertex_rule(Topology topology) {
  switch (topology) {
    case Topology::PointList: return {1, 1};
    case Topology::LineList: return {2, 2};
    case Topology::LineStrip: return {2, 1};
    case Topology::TriangleList: return {3, 3};
    case Topology::TriangleStrip:
    case Topology::TriangleFan: return {3, 1};
  }
  return {1, 1};
}

// Vulkan spec "Primitive Topologies": primitives formed by n vertices.
uint64_t primitive_count(Topology topology, uint64_t vertices) {
  switch (topology) {
    case Topology::PointList: return vertices;
    case Topology::LineList: return vertices / 2;
    case Topology::LineStrip: return vertices - 1;
    case Topology::TriangleList: return vertices / 3;
    case Topology::TriangleStrip:
    case Topology::TriangleFan: return vertices - 2;
  }
  return 0;
}

// One coordinate: a number, or with allow_non_finite the strings "nan", "inf", "-inf".
float read_coordinate(const Json& value, const Node& position, size_t axis, bool allow_non_finite) {
  if (value.is_number()) {
    const double coordinate = value.get<double>();
    if (allow_non_finite || std::fabs(coordinate) <= FLT_MAX) return float(coordinate);
    position.element(axis).fail("a finite number a float can hold");
  }
  if (value.is_string() && allow_non_finite) {
    const std::string& text = value.get_ref<const std::string&>();
    if (text == "nan") return std::numeric_limits<float>::quiet_NaN();
    if (text == "inf") return std::numeric_limits<float>::infinity();
    if (text == "-inf") return -std::numeric_limits<float>::infinity();
    position.element(axis).fail("a number, \"nan\", \"inf\" or \"-inf\"");
  }
  if (value.is_string()) {
    position.element(axis).fail("a number (the strings \"nan\", \"inf\", \"-inf\" need \"allow_non_finite\": true)");
  }
  position.element(axis).fail("a number");
}

glm::vec4 read_position(const Node& position, const PositionContext& context) {
  const bool world = context.space == PositionSpace::World;
  const Json& value = position.json();
  const bool sized = value.is_array() && (value.size() == 3 || (!world && value.size() == 4));
  if (!sized) position.fail(world ? "a world position [x, y, z]" : "a position [x, y, z] or [x, y, z, w]");
  glm::vec4 pos{0, 0, 0, 1};
  for (size_t axis = 0; axis < value.size(); ++axis) {
    pos[int(axis)] = read_coordinate(value[axis], position, axis, context.allow_non_finite);
  }
  return pos;
}

glm::vec4 to_clip(const glm::vec4& pos, const PositionContext& context) {
  switch (context.space) {
    case PositionSpace::Clip: return pos;
    case PositionSpace::Pixels: return pixels_to_clip(context.viewport, pos);
    case PositionSpace::World: return context.world_to_clip * pos;
  }
  return pos;
}

void check_clip_position(const Node& position, const glm::vec4& pos_clip, const PositionContext& context) {
  if (context.allow_non_finite) return;
  const char* after = context.space == PositionSpace::World    ? " after the camera transform"
                      : context.space == PositionSpace::Pixels ? " after the pixels-to-clip conversion"
                                                               : "";
  for (int axis = 0; axis < 4; ++axis) {
    if (!std::isfinite(pos_clip[axis])) {
      position.fail_message(fmt::format("expected a finite clip-space position, found {} in component {}{}",
                                        pos_clip[axis], axis, after));
    }
  }
  // w = 0 has no perspective division; only NaN/Inf experiments may ask for it.
  if (pos_clip.w == 0.0f) {
    position.fail_message(
        fmt::format("expected a clip-space w != 0 (w = 0 needs \"allow_non_finite\": true), found w = 0{}", after));
  }
}

std::vector<glm::vec4> read_positions(const Node& draw, const PositionContext& context) {
  const auto positions = draw.find("positions");
  if (!positions) draw.fail_message("expected the required key \"positions\" (an array of positions), found none");
  const size_t count = positions->expect_array(1, kMaxVertices, "a non-empty array of positions");
  std::vector<glm::vec4> positions_clip(count);
  for (size_t i = 0; i < count; ++i) {
    const Node position = positions->element(i);
    positions_clip[i] = to_clip(read_position(position, context), context);
    check_clip_position(position, positions_clip[i], context);
  }
  return positions_clip;
}

std::vector<uint32_t> read_indices(const Node& indices, size_t position_count) {
  const size_t count = indices.expect_array(1, kMaxVertices, "a non-empty array of indices");
  const std::string expected = fmt::format("an index < {} (the number of positions)", position_count);
  std::vector<uint32_t> result(count);
  for (size_t i = 0; i < count; ++i) {
    const Json& value = indices.json()[i];
    if (value.is_number_unsigned() && value.get<uint64_t>() < position_count) {
      result[i] = uint32_t(value.get<uint64_t>());
    } else {
      indices.element(i).fail(expected);
    }
  }
  return result;
}

// The optional "count": how many of the vertices (or indices) to draw, default all.
void apply_count(const Node& count, Draw& draw) {
  const bool indexed = !draw.indices.empty();
  const uint64_t available = indexed ? draw.indices.size() : draw.positions_clip.size();
  const int64_t wanted = count.as_integer(
      1, int64_t(available),
      fmt::format("a count in 1..{} (the number of {})", available, indexed ? "indices" : "positions"));
  if (indexed) {
    draw.indices.resize(size_t(wanted));
  } else {
    draw.positions_clip.resize(size_t(wanted));
  }
}

void check_primitives(const Node& vertices, const Draw& draw) {
  const uint64_t count = draw.vertex_count();
  const VertexRule rule = vertex_rule(draw.topology);
  const char* topology = to_string(draw.topology);
  if (count < rule.min || count % rule.multiple != 0) {
    const std::string need = rule.multiple > 1 ? fmt::format("a multiple of {} vertices", rule.multiple)
                                               : fmt::format("at least {} vertices", rule.min);
    vertices.fail_message(fmt::format("expected {} for {} (at least one whole primitive), found {} {}", need, topology,
                                      count, count == 1 ? "vertex" : "vertices"));
  }
  const uint64_t primitives = primitive_count(draw.topology, count);
  if (primitives > kMaxPrimitivesPerDraw) {
    vertices.fail_message(fmt::format("expected at most {} primitives per draw (owner ids keep 24 bits), found {} {}",
                                      kMaxPrimitivesPerDraw, primitives, topology));
  }
}

}  // namespace

Draw read_draw(const Node& node, const RasterState& defaults, const PositionContext& context) {
  node.expect_object("a draw object", {"name", "topology", "positions", "indices", "count", "cull", "front_face",
                                       "polygon_mode", "line_mode", "line_width", "depth_test", "depth_write",
                                       "depth_compare", "depth_bias", "depth_clamp", "depth_clip"});
  Draw draw;
  if (const auto name = node.find("name")) draw.name = name->as_line("a name string");
  if (const auto topology = node.find("topology")) {
    draw.topology = topology->as_enum({Topology::TriangleList, Topology::TriangleStrip, Topology::TriangleFan,
                                       Topology::LineList, Topology::LineStrip, Topology::PointList});
  }
  draw.positions_clip = read_positions(node, context);
  const auto indices = node.find("indices");
  if (indices) draw.indices = read_indices(*indices, draw.positions_clip.size());
  const auto count = node.find("count");
  if (count) apply_count(*count, draw);
  check_primitives(count ? *count : indices ? *indices : *node.find("positions"), draw);
  draw.state = read_draw_state(node, defaults);
  return draw;
}

}  // namespace rastercmp::scene_io_detail
