// Names of the scene enums. Each name is the spelling the scene format uses
// (docs/scene-format.md), so the loader parses by comparing with these.
#include "model/scene.hpp"

#include "model/depth_format.hpp"

namespace rastercmp {

const char* to_string(DepthFormat format) { return depth_format_info(format).name; }

const char* to_string(Topology topology) {
  switch (topology) {
    case Topology::PointList: return "point_list";
    case Topology::LineList: return "line_list";
    case Topology::LineStrip: return "line_strip";
    case Topology::TriangleList: return "triangle_list";
    case Topology::TriangleStrip: return "triangle_strip";
    case Topology::TriangleFan: return "triangle_fan";
  }
  return "?";
}

const char* to_string(CullMode mode) {
  switch (mode) {
    case CullMode::None: return "none";
    case CullMode::Front: return "front";
    case CullMode::Back: return "back";
    case CullMode::FrontAndBack: return "front_and_back";
  }
  return "?";
}

const char* to_string(FrontFace face) {
  switch (face) {
    case FrontFace::CounterClockwise: return "ccw";
    case FrontFace::Clockwise: return "cw";
  }
  return "?";
}

const char* to_string(PolygonMode mode) {
  switch (mode) {
    case PolygonMode::Fill: return "fill";
    case PolygonMode::Line: return "line";
    case PolygonMode::Point: return "point";
  }
  return "?";
}

const char* to_string(LineMode mode) {
  switch (mode) {
    case LineMode::Default: return "default";
    case LineMode::Rectangular: return "rectangular";
    case LineMode::Bresenham: return "bresenham";
    case LineMode::RectangularSmooth: return "rectangular_smooth";
  }
  return "?";
}

const char* to_string(CompareOp op) {
  switch (op) {
    case CompareOp::Never: return "never";
    case CompareOp::Less: return "less";
    case CompareOp::Equal: return "equal";
    case CompareOp::LessOrEqual: return "less_or_equal";
    case CompareOp::Greater: return "greater";
    case CompareOp::NotEqual: return "not_equal";
    case CompareOp::GreaterOrEqual: return "greater_or_equal";
    case CompareOp::Always: return "always";
  }
  return "?";
}

bool is_triangle_topology(Topology topology) {
  return topology == Topology::TriangleList || topology == Topology::TriangleStrip || topology == Topology::TriangleFan;
}

bool is_line_topology(Topology topology) { return topology == Topology::LineList || topology == Topology::LineStrip; }

uint32_t depth_bits(DepthFormat format) { return depth_format_info(format).bits; }

}  // namespace rastercmp
