// The fill, line and depth stages of the classic path for one sample per pixel: which pixels a
// primitive covers and the raw depth each gets (docs/methods.md "Selecting a method").
//  fill  exact       the set-up's 24.8 edge planes with the top-left bias, at pixel centres;
//        scanline    methods::fill_scanline_notes on the float window triangle shifted by -1/2
//                    (so the notes' integer sample points are pixel centres);
//        float_edge  methods::fill_triangle_edge_function, EdgeTieRule::None (E >= 0 on all edges);
//        even_odd / winding  methods::fill_polygon_rule at pixel centres;
//  line  exact       the set-up's line quad planes (Vulkan's line modes);
//        dda / bresenham  methods::line_dda / line_bresenham between the pixels holding the two
//                    window endpoints (both included), width 1;
//  depth exact / no_fma  the set-up's plane, z = a0 + dzdx px + dzdy py, fused or not (§3.3);
//        bilinear    methods::bilinear_depth_in_triangle at the pixel centre (edges, then span);
//        perspective_correct  methods::interpolate_perspective of window z with the clip w;
//        lines always take the plane. Then the depth bias, the clamps and the format conversion
//        of the exact path (depth_sample.hpp, §3.4-§3.5).
// Classic fills cover only pixels of the draw region (framebuffer ∩ scissor ∩ viewport).
#pragma once

#include <cstdint>
#include <functional>

#include "cpu_raster/classic/classic_front_end.hpp"

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
uint32_t fragment_depth_raw(const ClassicPrimitive& primitive, DepthMethod method, int32_t px, int32_t py);

}  // namespace rastercmp::cpu::classic
