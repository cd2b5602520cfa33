// Line set-up, lp_setup_line.c try_setup_line (docs/lavapipe-rules.md §5.2-§5.5, step 18).
// Both modes build a 4-corner quad in 24.8 fixed point from the two window endpoints and
// rasterize it with the same plane rule as triangles:
//  - rectangular (DEFAULT and RECTANGULAR, strictLines): endpoints and half-width offset snapped
//    separately with util_iround, width used as given;
//  - Bresenham: the GL diamond-exit parallelogram, ends moved by ±0.5 px along the major axis,
//    width rounded to whole pixels; multisampling is off for these lines.
// The depth plane is linear_coef's; lines get no depth bias (§4.4).
#pragma once

#include <array>

#include "cpu_raster/exact/setup_context.hpp"
#include "cpu_raster/exact/triangle_setup.hpp"

namespace rastercmp::cpu {

struct LineSetup {
  SetupFate fate = SetupFate::Rasterized;
  bool x_major = false;     // Bresenham only
  bool draw_start = false;  // Bresenham diamond-exit decisions
  bool draw_end = false;
  PixelRect bbox;  // unclamped, valid once snapped
  RasterPrimitive raster;
};

// Whether the line is rasterized with multisampling (lvp_pipeline.c disable_multisample).
bool line_rasterizes_per_sample(const SetupContext& context);

LineSetup setup_line(const std::array<WindowVertex, 2>& window, uint32_t owner, const SetupContext& context);

}  // namespace rastercmp::cpu
