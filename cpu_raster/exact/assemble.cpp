#include "cpu_raster/exact/assemble.hpp"

namespace rastercmp::cpu {
namespace {

// Position index of the draw's k-th vertex (through the index buffer when there is one).
uint32_t resolve(const Draw& draw, uint32_t k) { return draw.indices.empty() ? k : draw.indices[k]; }

// The draw's vertex numbers (before index resolution) of primitive i.
std::array<uint32_t, 3> vertex_numbers(Topology topology, uint32_t i) {
  switch (topology) {
    case Topology::TriangleList: return {3 * i, 3 * i + 1, 3 * i + 2};
    case Topology::TriangleStrip:
      return (i % 2 == 0) ? std::array<uint32_t, 3>{i, i + 1, i + 2} : std::array<uint32_t, 3>{i, i + 2, i + 1};
    case Topology::TriangleFan: return {i + 1, i + 2, 0};
    case Topology::LineList: return {2 * i, 2 * i + 1, 0};
    case Topology::LineStrip: return {i, i + 1, 0};
    case Topology::PointList: return {i, 0, 0};
  }
  return {0, 0, 0};
}

}  // namespace

uint32_t primitive_count(const Draw& draw) {
  const uint32_t n = draw.vertex_count();
  switch (draw.topology) {
    case Topology::TriangleList: return n / 3;
    case Topology::TriangleStrip:
    case Topology::TriangleFan: return n >= 3 ? n - 2 : 0;
    case Topology::LineList: return n / 2;
    case Topology::LineStrip: return n >= 2 ? n - 1 : 0;
    case Topology::PointList: return n;
  }
  return 0;
}

AssembledPrimitive assemble_primitive(const Draw& draw, uint32_t primitive_index) {
  AssembledPrimitive primitive;
  primitive.primitive_index = primitive_index;
  primitive.vertex_count = is_triangle_topology(draw.topology) ? 3 : is_line_topology(draw.topology) ? 2 : 1;
  const std::array<uint32_t, 3> numbers = vertex_numbers(draw.topology, primitive_index);
  for (uint32_t k = 0; k < primitive.vertex_count; ++k) primitive.position[k] = resolve(draw, numbers[k]);
  return primitive;
}

}  // namespace rastercmp::cpu
