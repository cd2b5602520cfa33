// Cull stage "normal_dot_view": back-face culling by N·V in clip space, before clipping, instead
// of the sign of the snapped window-space area (docs/lavapipe-rules.md §2.3). The triangle's vertices are
// taken as points (x, y, w) of homogeneous clip space, where the eye sits at the origin and every
// vertex is seen along the ray from it; N = (v1 - v0) x (v2 - v0) and V = eye - v0 (methods::
// is_back_face, notes NLC "Back Face Removal": hidden if N·V <= 0). With w > 0 and a viewport of
// positive height, N·V > 0 exactly when the window-space triangle is counter-clockwise in
// Vulkan's sense, so this agrees with the exact cull except where snapping changes the sign and
// where the viewport flips y (negative height), which clip space cannot see.
#pragma once

#include <array>

#include <glm/vec4.hpp>

#include "cpu_raster/methods/geometry.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::classic {

// The test's decision variables: N (turned for a clockwise front face), V = eye - v0, N·V, and
// what the cull mode makes of them.
struct NormalDotView {
  methods::Vec3 normal{}, view{};
  double n_dot_v = 0;
  bool back = false;    // N·V <= 0
  bool culled = false;  // by the cull mode (None: never, FrontAndBack: always)
};
NormalDotView normal_dot_view(const std::array<glm::vec4, 3>& pos_clip, CullMode cull, FrontFace front_face);

// True when the cull mode removes the triangle by the N·V test (edge-on faces count as back).
inline bool normal_dot_view_culls(const std::array<glm::vec4, 3>& pos_clip, CullMode cull, FrontFace front_face) {
  return normal_dot_view(pos_clip, cull, front_face).culled;
}

}  // namespace rastercmp::cpu::classic
