// The per-vertex clip test and the clip planes (docs/lavapipe-rules.md §1.3, §1.5; step 3).
// Bits are set with LLVM's unordered compares, so a NaN coordinate counts as outside.
// Only the 0 <= z <= w depth planes of Vulkan's 0..1 clip depth are modelled.
#pragma once

#include <cstdint>

#include <glm/vec4.hpp>

namespace rastercmp::cpu {

enum ClipPlane : uint32_t {
  kClipRight = 0,   // x > w        plane (-1, 0, 0, 1)
  kClipLeft = 1,    // 0 > x + w    plane ( 1, 0, 0, 1)
  kClipBottom = 2,  // y > w        plane ( 0,-1, 0, 1)
  kClipTop = 3,     // 0 > y + w    plane ( 0, 1, 0, 1)
  kClipNear = 4,    // 0 > z        plane ( 0, 0, 1, 0)   (halfz)
  kClipFar = 5,     // z > w        plane ( 0, 0,-1, 1)
  kClipPlaneCount = 6,
};

// Bit k set: the vertex is outside plane k. The depth bits only when depth clipping is on.
uint32_t clip_mask(const glm::vec4& pos_clip, bool depth_clip);

// The planes the clip test checks: x and y always, the depth planes only with depth clipping.
inline uint32_t tested_clip_planes(bool depth_clip) { return depth_clip ? 0x3Fu : 0x0Fu; }

// Signed distance to plane k as draw_pipe_clip.c dot4 computes it: ((a0b0 + a1b1) + a2b2) + a3b3.
float plane_distance(const glm::vec4& pos_clip, uint32_t plane);

}  // namespace rastercmp::cpu
