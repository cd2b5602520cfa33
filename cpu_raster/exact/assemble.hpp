// Primitive assembly: the vertices of primitive i of a draw, in the order lavapipe hands them to
// set-up with the provoking vertex FIRST (draw_decompose_tmp.h, lp_setup_vbuf.c):
//   triangle list  i -> (3i, 3i+1, 3i+2)
//   triangle strip i -> (i, i+1, i+2) for even i, (i, i+2, i+1) for odd i
//   triangle fan   i -> (i+1, i+2, 0)
//   line list      i -> (2i, 2i+1)
//   line strip     i -> (i, i+1)
// Indices are resolved, so the result names positions of Draw::positions_clip.
// Point lists are not assembled here (the profile does not reproduce points).
#pragma once

#include <array>
#include <cstdint>

#include "model/scene.hpp"

namespace rastercmp::cpu {

struct AssembledPrimitive {
  uint32_t primitive_index = 0;        // gl_PrimitiveID
  std::array<uint32_t, 3> position{};  // indices into Draw::positions_clip
  uint32_t vertex_count = 0;           // 3 for triangles, 2 for lines
};

// Number of primitives the draw's vertex count forms under its topology.
uint32_t primitive_count(const Draw& draw);

AssembledPrimitive assemble_primitive(const Draw& draw, uint32_t primitive_index);

}  // namespace rastercmp::cpu
