#include "cpu_raster/draw_chunks.hpp"

#include "cpu_raster/assemble.hpp"
#include "cpu_raster/clip_test.hpp"

namespace rastercmp::cpu {

uint32_t segment_size(const Draw& draw) { return draw.indices.empty() ? 4096 : 1024; }  // draw_pt_vsplit.c

uint32_t primitives_per_chunk(const Draw& draw) {
  const uint32_t s = segment_size(draw);
  switch (draw.topology) {
    case Topology::PointList: return s;
    case Topology::LineList: return s / 2;
    case Topology::LineStrip: return s - 1;                // consecutive segments share a vertex
    case Topology::TriangleList: return s / 3;             // whole triangles: 1023 / 4095 vertices
    case Topology::TriangleStrip: return s - 2;            // consecutive segments share two vertices
    case Topology::TriangleFan: return s - 2;              // ... and every segment the first vertex
  }
  return s;
}

std::vector<bool> pipelined_chunks(const Draw& draw, bool depth_clip) {
  const uint32_t count = primitive_count(draw), per_chunk = primitives_per_chunk(draw);
  std::vector<bool> pipelined((count + per_chunk - 1) / per_chunk, false);
  std::vector<int8_t> clipped(draw.positions_clip.size(), -1);  // clip test per position, once
  const auto is_clipped = [&](uint32_t position) {
    if (clipped[position] < 0) clipped[position] = clip_mask(draw.positions_clip[position], depth_clip) != 0;
    return clipped[position] == 1;
  };
  for (uint32_t i = 0; i < count; ++i) {
    if (pipelined[i / per_chunk]) continue;
    const AssembledPrimitive prim = assemble_primitive(draw, i);
    for (uint32_t k = 0; k < prim.vertex_count; ++k)
      if (is_clipped(prim.position[k])) pipelined[i / per_chunk] = true;
  }
  return pipelined;
}

}  // namespace rastercmp::cpu
