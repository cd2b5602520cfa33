// The fill, line and depth stages of the classic path for one sample per pixel: which pixels a
// primitive covers and the raw depth each gets (docs/methods.md "Selecting a method").
//  fill  exact       the set-up's 24.8 edge planes with the top-left bias, at pixel centres;
//        scanline    methods::fill_scanline_notes on the float window triangle shifted by -1/2
//                    (so the notes' integer sample points are pixel centres);
//        float_edge  methods::fill_triangle_edge_function, EdgeTieRule::None (E >= 0 on all edges);
//        even_odd / winding  methods::fill_polygon_rule at pixel centres;
//        flood       the Bresenham outline between the vertices' pixels, then methods::flood_fill
//                    (4-connected) from one seed pixel inside; outline and filled cells are covered;
//  line  exact       the set-up's line quad planes (Vulkan's line modes);
//        dda / bresenham  methods::line_dda / line_bresenham between the pixels holding the two
//                    window endpoints (both included), width 1;
//  depth exact / no_fma  the set-up's plane, z = a0 + dzdx px + dzdy py, fused or not (§3.3);
//        bilinear    methods::bilinear_depth_in_triangle at the pixel centre (edges, then span);
//        perspective_correct  methods::interpolate_perspective of window z with the clip w;
//        pseudo_depth_F  methods::pseudo_depth of the eye distance w (1/w interpolated in window
//                    space), near 25, far F, stored as (1 - pz) / 2 (lines too);
//        other methods: lines take the plane. Then the depth bias, the clamps and the format conversion
//        of the exact path (depth_sample.hpp, §3.4-§3.5).
// Classic fills cover only pixels of the draw region (framebuffer ∩ scissor ∩ viewport).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>

#include "cpu_raster/classic/classic_front_end.hpp"
#include "cpu_raster/methods/fill_flood.hpp"

namespace rastercmp::cpu::classic {

struct Fragment {
  int32_t x = 0, y = 0;
  uint32_t depth_raw = 0;  // meaningful when the primitive's depth test is active
};

using FragmentSink = std::function<void(const Fragment&)>;

// Fragments in row order (dda / bresenham: in the line method's own pixel order).
void for_each_fragment(const ClassicPrimitive& primitive, const ClassicMethods& chosen, const PixelRect& region,
                       const FragmentSink& sink);

// The stored depth of the primitive at pixel (px, py) by the depth method.
uint32_t fragment_depth_raw(const ClassicPrimitive& primitive, const ClassicMethods& chosen, int32_t px, int32_t py);

// line=dda / bresenham: the pixels holding the two window endpoints, between which the line
// method runs (methods::line_dda_trace / line_bresenham_trace give its steps).
std::array<methods::PixelXY, 2> line_method_endpoints(const ClassicPrimitive& primitive);

// depth=perspective_correct at the pixel centre: the window-space barycentrics, 1/w per vertex and
// at the sample, and window z interpolated linearly and with the 1/w correction (the latter is
// what the method stores, before bias, clamp and format conversion).
struct PerspectiveTrace {
  std::array<double, 3> lambda{};  // methods::barycentric_window of the pixel centre
  std::array<double, 3> inv_w{};   // 1 / w_clip of each vertex
  double inv_w_at = 0;             // sum lambda_i / w_i
  double z_linear = 0;             // sum lambda_i z_i
  double z_perspective = 0;        // (sum lambda_i z_i / w_i) / (sum lambda_i / w_i)
};
PerspectiveTrace perspective_trace(const ClassicPrimitive& primitive, int32_t px, int32_t py);

// depth=pseudo_depth_*: (1 - pz) / 2 of the eye distance w at the pixel centre (near 25), before
// bias, clamp and format conversion.
double pseudo_depth_value(const ClassicPrimitive& primitive, double far_distance, int32_t px, int32_t py);

// fill=flood on one triangle: the grid over the outline's pixel box ∩ draw region, holding the
// Bresenham outline, the flood-filled cells and the empty rest; the seed (none when no pixel
// centre inside the triangle is off the outline).
inline constexpr uint32_t kFloodEmpty = 0, kFloodOutline = 1, kFloodFilled = 2;
struct FloodTrace {
  methods::CellGrid grid;  // cell (x, y) is pixel (x + origin.x, y + origin.y)
  methods::PixelXY origin{};
  std::optional<methods::PixelXY> seed;  // in pixels
  uint64_t filled = 0;
};
FloodTrace flood_trace(const ClassicPrimitive& primitive, const PixelRect& region);

}  // namespace rastercmp::cpu::classic
