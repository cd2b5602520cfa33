// Draw state keys: the "defaults" object and the state part of each draw (docs/scene-format.md).
#include "model/scene_io_draw.hpp"

namespace rastercmp::scene_io_detail {

using scene_json::Node;

namespace {

// lineWidthRange = [1, 255] (docs/lavapipe-rules.md §0, device properties).
constexpr double kMinLineWidth = 1;
constexpr double kMaxLineWidth = 255;

// "depth_bias": {constant, slope, clamp, enable}; its presence turns the bias on.
DepthBias read_depth_bias(const Node& node) {
  node.expect_object("a depth bias object {\"constant\", \"slope\", \"clamp\", \"enable\"}",
                     {"constant", "slope", "clamp", "enable"});
  DepthBias bias;
  bias.enable = true;
  if (const auto constant = node.find("constant")) bias.constant_factor = constant->as_float("a finite number");
  if (const auto slope = node.find("slope")) bias.slope_factor = slope->as_float("a finite number");
  if (const auto clamp = node.find("clamp")) bias.clamp = clamp->as_float("a finite number");
  if (const auto enable = node.find("enable")) bias.enable = enable->as_bool();
  return bias;
}

}  // namespace

RasterState read_draw_state(const Node& object, RasterState base) {
  RasterState state = base;
  if (const auto node = object.find("cull")) {
    state.cull_mode = node->as_enum({CullMode::None, CullMode::Front, CullMode::Back, CullMode::FrontAndBack});
  }
  if (const auto node = object.find("front_face")) {
    state.front_face = node->as_enum({FrontFace::CounterClockwise, FrontFace::Clockwise});
  }
  if (const auto node = object.find("polygon_mode")) {
    state.polygon_mode = node->as_enum({PolygonMode::Fill, PolygonMode::Line, PolygonMode::Point});
  }
  if (const auto node = object.find("line_mode")) {
    state.line_mode =
        node->as_enum({LineMode::Default, LineMode::Rectangular, LineMode::Bresenham, LineMode::RectangularSmooth});
  }
  if (const auto node = object.find("line_width")) {
    state.line_width = float(node->as_number(kMinLineWidth, kMaxLineWidth, "a line width in 1..255 (lineWidthRange)"));
  }
  if (const auto node = object.find("depth_test")) state.depth.test_enable = node->as_bool();
  if (const auto node = object.find("depth_write")) state.depth.write_enable = node->as_bool();
  if (const auto node = object.find("depth_compare")) {
    state.depth.compare_op =
        node->as_enum({CompareOp::Never, CompareOp::Less, CompareOp::Equal, CompareOp::LessOrEqual, CompareOp::Greater,
                       CompareOp::NotEqual, CompareOp::GreaterOrEqual, CompareOp::Always});
  }
  if (const auto node = object.find("depth_bias")) state.depth_bias = read_depth_bias(*node);
  if (const auto node = object.find("depth_clamp")) state.depth_clamp = node->as_bool();
  if (const auto node = object.find("depth_clip")) state.depth_clip = node->as_bool();
  return state;
}

RasterState read_defaults(const Node& defaults) {
  defaults.expect_object("an object of draw state keys",
                         {"cull", "front_face", "polygon_mode", "line_mode", "line_width", "depth_test", "depth_write",
                          "depth_compare", "depth_bias", "depth_clamp", "depth_clip"});
  return read_draw_state(defaults, RasterState{});
}

}  // namespace rastercmp::scene_io_detail
