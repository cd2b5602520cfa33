// A vertex between the clip test and set-up: its clip-space position, its window position and
// where that window position came from (docs/lavapipe-rules.md §1.3, §1.6).
#pragma once

#include <cstdint>

#include <glm/vec4.hpp>

#include "cpu_raster/exact/viewport.hpp"

namespace rastercmp::cpu {

struct ClipVertex {
  glm::vec4 pos_clip{0, 0, 0, 1};
  WindowVertex window;     // JIT window coordinates, or C ones for a vertex the clipper made
  uint32_t clip_mask = 0;  // outside-plane bits of an original vertex (0 for new vertices)
  bool made_by_clipper = false;
};

// An original vertex: clip test, then the JIT viewport transform.
ClipVertex make_clip_vertex(const glm::vec4& pos_clip, const ViewportTransform& viewport, bool depth_clip, bool fma);

// draw_pipe_clip.c interp(): pos = out + t*(in - out) per component, window coordinates in C.
ClipVertex interpolate_clip_vertex(float t, const ClipVertex& out, const ClipVertex& in,
                                   const ViewportTransform& viewport);

}  // namespace rastercmp::cpu
