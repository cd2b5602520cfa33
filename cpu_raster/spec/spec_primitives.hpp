// The spec profile's geometry: every primitive of every draw, assembled, clipped and transformed
// by the exact path's own stages (cpu::assemble_primitive, cpu::clip_triangle, cpu::clip_line,
// lavapipe's viewport arithmetic). That is allowed: Vulkan fixes what clipping keeps, not how
// ("Primitive Clipping": the algorithm and the triangulation are open, docs/lavapipe-rules.md §1.1), and
// the tolerance boxes absorb the float differences between clippers and viewport transforms.
// Each piece then gets what the classification needs: its snapped cells or line regions, its
// facing gate and what decides its depth test against the clear value, sample by sample.
// Pieces that are certainly culled, or draws whose state writes nothing, are left out.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "cpu_raster/exact/viewport.hpp"
#include "cpu_raster/spec/depth_gate.hpp"
#include "cpu_raster/spec/line_coverage.hpp"
#include "cpu_raster/spec/triangle_coverage.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::spec {

struct SpecTriangle {
  uint32_t draw_index = 0, primitive_index = 0;
  std::array<WindowVertex, 3> window{};    // the piece, in emit order (window pixels, float)
  std::array<glm::vec4, 3> source_clip{};  // the primitive before clipping
  SnappedTriangle snapped;
  Gate facing = Gate::Certain;  // culling: certainly kept, possibly culled
  // False when a vertex the clipper made has w_c <= 0: the clipped polygon lies in the clip volume,
  // -w_c <= x_c, y_c <= w_c, so its exact vertex sits at w_c = 0 and x_c = y_c = 0 (within rounding),
  // where the projection divides 0 by 0 and the polygon's window image has no area. The piece's
  // window shape is rounding noise then: it may cover samples, never certainly.
  bool shape_certain = true;
  DepthJudge depth;
};

struct SpecLine {
  uint32_t draw_index = 0, primitive_index = 0;
  LineShape shape;
  DepthJudge depth;
};

struct SpecPrimitives {
  std::vector<SpecTriangle> triangles;
  std::vector<SpecLine> lines;
  // Some primitive that may be drawn has a non-finite or out-of-range coordinate, or was dropped
  // by lavapipe's clipper for an Inf/NaN plane distance: the spec says nothing about what it
  // covers, so anything inside the scissor may be covered.
  bool undefined = false;
};

// Vulkan "Basic Polygon Rasterization": a > 0 is front-facing for COUNTER_CLOCKWISE, zero-area
// triangles are back-facing. area_sign 0 (facing uncertain under snapping) culls possibly.
Gate facing_gate(const RasterState& state, int area_sign);

// The gate of a triangle's fragment in the box centred on pixel (px, py).
Gate triangle_gate_at(const SpecTriangle& triangle, int32_t px, int32_t py);

SpecPrimitives build_spec_primitives(const Scene& scene, bool fma, uint32_t sub_pixel_bits);

// The viewport rectangle in window pixels: the image of the clip volume -w_c <= x_c, y_c <= w_c
// (Vulkan "Primitive Clipping", "Controlling the Viewport"), where every clipped primitive lies.
struct ViewportRect {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};
ViewportRect viewport_rect(const Viewport& v);

// The box lies strictly inside the viewport rectangle: its sides bound a triangle's clipped
// polygon as its edges do, so a box across them cannot be FULL (the same rule as for lines).
bool box_inside_viewport(const ViewportRect& r, const ToleranceBox& box, uint32_t bits);

// FULL only for a piece whose shape is certain, and inside the viewport rectangle.
Coverage capped(Coverage coverage, const SpecTriangle& t, const ViewportRect& viewport, const ToleranceBox& box,
                uint32_t bits);

// One primitive's own class at pixel (px, py), as the coverage map adds it (the union's Must also
// comes from shared edges, coverage_map.hpp).
Coverage triangle_coverage_at(const SpecTriangle& t, const ViewportRect& viewport, int32_t px, int32_t py,
                              uint32_t bits, bool multisample);
Coverage line_coverage_at(const SpecLine& line, int32_t px, int32_t py, uint32_t bits, bool multisample);

}  // namespace rastercmp::cpu::spec
