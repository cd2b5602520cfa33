// The driver's draw chunks and their "pipelined" flag (lavapipe-rules §1.5). vsplit cuts a draw
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

#include <cstdint>
#include <vector>

#include "model/scene.hpp"

namespace rastercmp::cpu {

// vsplit's segment size for the draw: 1024 indices, or 4096 vertices when not indexed.
uint32_t segment_size(const Draw& draw);

// How many primitives of the draw's topology one chunk holds.
uint32_t primitives_per_chunk(const Draw& draw);

// Per chunk, in order: whether any vertex used by the chunk's primitives has a clip-mask bit.
std::vector<bool> pipelined_chunks(const Draw& draw, bool depth_clip);

}  // namespace rastercmp::cpu
