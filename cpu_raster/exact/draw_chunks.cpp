#include "cpu_raster/exact/draw_chunks.hpp"

#include "cpu_raster/exact/clip_test.hpp"

namespace rastercmp::cpu {

uint32_t segment_size(const Draw& draw) { return draw.indices.empty() ? 4096 : 1024; }  // draw_pt_vsplit.c

uint32_t primitives_per_chunk(const Draw& draw) {
  const uint32_t s = segment_size(draw);
  switch (draw.topology) {
    case Topology::PointList: return s;
    case Topology::LineList: return s / 2;
    case Topology::LineStrip: return s - 1;      // consecutive segments share a vertex
    case Topology::TriangleList: return s / 3;   // whole triangles: 1023 / 4095 vertices
    case Topology::TriangleStrip: return s - 2;  // consecutive segments share two vertices
    case Topology::TriangleFan: return s - 2;    // ... and every segment the first vertex
  }
  return s;
}

ChunkVertices chunk_vertices(Topology topology, uint32_t first, uint32_t last) {
  switch (topology) {
    case Topology::PointList: return {first, last};
    case Topology::LineList: return {2 * first, 2 * last};
    case Topology::LineStrip: return {first, last + 1};
    case Topology::TriangleList: return {3 * first, 3 * last};
    case Topology::TriangleStrip: return {first, last + 2};
    case Topology::TriangleFan: return {first + 1, last + 2, true};
  }
  return {first, last};
}

std::vector<bool> pipelined_chunks(const Draw& draw, bool depth_clip) {
  return pipelined_chunks_by(
      draw, [&](uint32_t position) { return clip_mask(draw.positions_clip[position], depth_clip) != 0; });
}

}  // namespace rastercmp::cpu
