// Interpolation of a vertex attribute across a projected triangle: linear in window space
// (Gouraud, the notes' "Using Interpolation") and perspective-correct with 1/w.
//
// With window-space barycentric weights l_i of a pixel and clip w_i of the vertices:
//   linear:               a = sum l_i a_i
//   perspective-correct:  a = (sum l_i a_i / w_i) / (sum l_i / w_i)
// Depth z_ndc = z_clip / w_clip is itself an affine function of window x, y, so it is the one
// quantity that linear interpolation gets right (Vulkan: "z ... determined using linear
// interpolation", docs/lavapipe-rules.md §3.1); the notes' bilinear pseudo-depth relies on that.
//
// Does: window-space barycentrics of a point, both interpolations.
// Does not: clip (w must be non-zero with one sign across the triangle), or handle degenerate
//       triangles (barycentrics of a zero-area triangle are NaN).
#pragma once

#include <array>

#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

// Weights l_i with p = sum l_i v_i and sum l_i = 1.
std::array<double, 3> barycentric_window(const std::array<Vec2, 3>& pos_window, Vec2 p);

double interpolate_linear(const std::array<double, 3>& weights_window, const std::array<double, 3>& attribute);

double interpolate_perspective(const std::array<double, 3>& weights_window, const std::array<double, 3>& attribute,
                               const std::array<double, 3>& w_clip);

}  // namespace rastercmp::methods
