// Viewport transform (docs/lavapipe-rules.md §1.2, §1.3, §1.6; steps 2 and 4).
// Two evaluations exist in lavapipe and both are modelled:
//  - original vertices: the JIT's x*(1/w) then llvm.fmuladd(., scale, translate);
//  - vertices the clipper creates: C code ((x*(1/w))*scale)+translate, never fused.
#pragma once

#include <glm/vec4.hpp>

#include "model/scene.hpp"

namespace rastercmp::cpu {

// A vertex in framebuffer space: x, y in pixels (y down), z after the depth range transform.
struct WindowVertex {
  float x = 0, y = 0, z = 0;
};

struct ViewportTransform {
  float scale[3] = {0, 0, 0};
  float translate[3] = {0, 0, 0};
  float zmin = 0, zmax = 1;  // depth clamp range, util_viewport_zmin_zmax (float)
};

// lvp_execute.c get_viewport_xform / set_viewport_depth_xform (0..1 clip depth).
ViewportTransform make_viewport_transform(const Viewport& viewport);

// Original vertex, JIT path: oow = 1/w, FMA?(x*oow, scale, translate).
WindowVertex window_from_clip_jit(const glm::vec4& pos_clip, const ViewportTransform& viewport, bool fma);

// New vertex made by the clipper, C path: ((x*oow)*scale)+translate with two roundings.
WindowVertex window_from_clip_c(const glm::vec4& pos_clip, const ViewportTransform& viewport);

}  // namespace rastercmp::cpu
