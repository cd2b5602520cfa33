// The driver's draw chunks and their "pipelined" flag (docs/lavapipe-rules.md §1.5). vsplit cuts a draw
// into segments of at most 1024 indices (indexed draws) or 4096 vertices; a chunk in which any
// vertex its primitives use has a clip-mask bit goes whole through the draw pipeline, whose float
// cull (§2.6) can drop slivers the fixed-point set-up would keep.
//
// Measured on lavapipe 22.3.6 (a sliver whose float and fixed-point facings disagree, placed at
// every primitive position around the boundaries, with a clipped triangle before it): triangle
// lists take 341 triangles per chunk indexed (1023 indices) and 1365 non-indexed (4095
// vertices), strips and fans 1022 and 4094 (segments overlap by two vertices; a fan's first
// vertex belongs to every chunk); repeated indices do not change the count, and vertices that
// lie between used indices but are not used themselves do not count. Lines carry the flag but
// nothing of theirs depends on it; their chunks (512 / 2048 lines per list, 1023 / 4095 per
// strip) follow the same segment sizes and are not checked against the driver.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "cpu_raster/exact/assemble.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

// vsplit's segment size for the draw: 1024 indices, or 4096 vertices when not indexed.
uint32_t segment_size(const Draw& draw);

// How many primitives of the draw's topology one chunk holds.
uint32_t primitives_per_chunk(const Draw& draw);

// The vertex numbers (before index lookup) the primitives [first, last) use: lists and strips a
// run, fans their hub and a run (assemble.cpp's order, docs/lavapipe-rules.md §1.5).
struct ChunkVertices {
  uint32_t begin = 0, end = 0;
  bool hub = false;  // a fan: vertex 0 as well
};
ChunkVertices chunk_vertices(Topology topology, uint32_t first, uint32_t last);

// How many chunks the draw is cut into.
inline uint32_t chunk_count(const Draw& draw) {
  const uint32_t per_chunk = primitives_per_chunk(draw);
  return (primitive_count(draw) + per_chunk - 1) / per_chunk;
}

// Whether `is_clipped(position)` holds for a vertex chunk c's primitives use.
template <class IsClipped>
bool chunk_pipelined_by(const Draw& draw, uint32_t c, IsClipped is_clipped) {
  const uint32_t count = primitive_count(draw), per_chunk = primitives_per_chunk(draw);
  const auto position = [&](uint32_t k) { return draw.indices.empty() ? k : draw.indices[k]; };
  const ChunkVertices v = chunk_vertices(draw.topology, c * per_chunk, std::min(count, (c + 1) * per_chunk));
  bool clipped = v.hub && is_clipped(position(0));
  for (uint32_t k = v.begin; k < v.end && !clipped; ++k) clipped = is_clipped(position(k));
  return clipped;
}

// Per chunk, in order: chunk_pipelined_by.
template <class IsClipped>
std::vector<bool> pipelined_chunks_by(const Draw& draw, IsClipped is_clipped) {
  std::vector<bool> pipelined(chunk_count(draw), false);
  for (uint32_t c = 0; c < pipelined.size(); ++c) pipelined[c] = chunk_pipelined_by(draw, c, is_clipped);
  return pipelined;
}

// pipelined_chunks_by with the clip test of clip_test.hpp.
std::vector<bool> pipelined_chunks(const Draw& draw, bool depth_clip);

}  // namespace rastercmp::cpu
