#include "soak/primitives.hpp"

namespace rastercmp::soak {

uint32_t vertices_per_primitive(Topology topology) {
  switch (topology) {
    case Topology::PointList: return 1;
    case Topology::LineList:
    case Topology::LineStrip: return 2;
    case Topology::TriangleList:
    case Topology::TriangleStrip:
    case Topology::TriangleFan: return 3;
  }
  return 3;
}

uint64_t primitive_count(const Draw& draw) {
  const uint64_t n = draw.vertex_count();
  switch (draw.topology) {
    case Topology::PointList: return n;
    case Topology::LineList: return n / 2;
    case Topology::LineStrip: return n >= 2 ? n - 1 : 0;
    case Topology::TriangleList: return n / 3;
    case Topology::TriangleStrip:
    case Topology::TriangleFan: return n >= 3 ? n - 2 : 0;
  }
  return 0;
}

uint64_t primitive_count(const Scene& scene) {
  uint64_t total = 0;
  for (const Draw& d : scene.draws) total += primitive_count(d);
  return total;
}

std::vector<uint32_t> primitive_vertices(const Draw& draw, uint64_t p) {
  const uint32_t i = uint32_t(p);
  std::vector<uint32_t> v;
  switch (draw.topology) {
    case Topology::PointList: v = {i}; break;
    case Topology::LineList: v = {2 * i, 2 * i + 1}; break;
    case Topology::LineStrip: v = {i, i + 1}; break;
    case Topology::TriangleList: v = {3 * i, 3 * i + 1, 3 * i + 2}; break;
    case Topology::TriangleStrip: v = {i, i + 1 + i % 2, i + 2 - i % 2}; break;
    case Topology::TriangleFan: v = {i + 1, i + 2, 0}; break;
  }
  if (!draw.indices.empty())
    for (uint32_t& x : v) x = draw.indices[x];
  return v;
}

}  // namespace rastercmp::soak
