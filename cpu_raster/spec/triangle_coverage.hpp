// Must / may / must-not coverage of one triangle (after clipping), the construction of the CTS
// verifier's calculateTriangleCoverage (docs/spec-profile.md) made sound for every sample:
//  - every vertex may snap to any corner of its SnapCell (floor or ceiling per coordinate), so an
//    edge has 4 x 4 = 16 variants;
//  - FULL: the facing is the same for every variant, and the tolerance box lies strictly inside
//    every variant of every edge. Edge values are multilinear in the vertex coordinates, so the
//    corners of the cells bound every position inside them, not only the 16 variants;
//  - NONE: the box misses the convex hull of all cell corners, which holds every variant;
//  - PARTIAL otherwise ("could be full, partial or none depending on rounding and/or fill rules").
// The CTS answers NONE for a triangle small enough to sit inside the box; the hull test answers
// PARTIAL there. Samples exactly on an edge are PARTIAL: the tie rule is the device's choice
// (Vulkan "Basic Polygon Rasterization" mandates no particular rule, docs/lavapipe-rules.md §2.1).
#pragma once

#include <array>
#include <vector>

#include <glm/vec2.hpp>

#include "cpu_raster/spec/subpixel.hpp"

namespace rastercmp::cpu::spec {

enum class Coverage { None, Partial, Full };

struct SnappedTriangle {
  std::array<SnapCell, 3> cell{};
  // Sign of Vulkan's area a = -1/2 Σ (x_i y_{i+1} - x_{i+1} y_i) (framebuffer coordinates, y down;
  // a > 0 is counter-clockwise on screen) when every vertex placement within its cell widened by
  // one grid unit agrees on it; 0 when rounding could flip or flatten the triangle.
  int area_sign = 0;
  // Edge i runs from vertex i to vertex (i+1)%3; its 16 variants are oriented so that the
  // triangle's side is positive. Valid when area_sign != 0.
  std::array<std::array<LineEquation, 16>, 3> edge{};
  std::vector<GridPoint> hull;                         // convex hull of the 12 cell corners, counter-clockwise (y up)
  int64_t x_min = 0, x_max = 0, y_min = 0, y_max = 0;  // bounds of the hull
};

// pos_window: window x, y in pixels (finite, |v| <= kMaxWindowMagnitude).
SnappedTriangle snap_triangle(const std::array<glm::dvec2, 3>& pos_window, uint32_t bits);

// The box is strictly on the triangle's side of every variant of edge `edge`.
bool box_inside_edge(const SnappedTriangle& triangle, int edge, const ToleranceBox& box);

// The box misses every placement of the triangle.
bool box_outside(const SnappedTriangle& triangle, const ToleranceBox& box);

Coverage classify_box(const SnappedTriangle& triangle, const ToleranceBox& box);

// Row py of pixels at once: edge values are linear in x, so each of the tests above holds on a
// half-line of pixel columns. `full_*`: the pixels classify_box calls FULL; `touch_*`: the pixels
// whose boxes are not outside (empty spans have last < first). Exactly classify_box's answers;
// pixels in the touch span but not the full span still need classify_box (NONE or PARTIAL).
struct RowSpans {
  int64_t full_first = 0, full_last = -1;
  int64_t touch_first = 0, touch_last = -1;
};
RowSpans row_spans(const SnappedTriangle& triangle, int32_t py, uint32_t bits, bool multisample);

}  // namespace rastercmp::cpu::spec
