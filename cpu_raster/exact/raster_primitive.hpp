// What set-up hands the rasterizer: a convex region given as planes (3 triangle edges or 4 line
// quad edges, plus the scissor planes llvmpipe adds), the pixels to visit, and the depth plane.
// A sample is covered iff every plane's value there is > 0 (docs/lavapipe-rules.md §2.4, §2.5, §6).
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "cpu_raster/exact/binned_triangle.hpp"
#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/draw_region.hpp"
#include "cpu_raster/exact/edge_plane.hpp"
#include "cpu_raster/exact/fixed_point.hpp"

namespace rastercmp::cpu {

// Standard 4x sample locations (§6): lp_rast.c lp_sample_pos_4x, in fixed units iround(pos*256).
struct SampleOffset {
  int32_t x_fixed, y_fixed;
  float x, y;
};
inline constexpr std::array<SampleOffset, 4> kStandardSamples4x = {{
    {96, 32, 0.375f, 0.125f},
    {224, 96, 0.875f, 0.375f},
    {32, 160, 0.125f, 0.625f},
    {160, 224, 0.625f, 0.875f},
}};

// Where a sample is tested (snapped frame, fixed units) and where its depth is interpolated.
struct SamplePoint {
  int64_t x_fixed = 0, y_fixed = 0;
  float x = 0, y = 0;
};

struct RasterPrimitive {
  uint32_t owner = 0;
  bool is_line = false;
  uint32_t edge_count = 0;  // planes [0, edge_count) are the primitive's edges, the rest scissor planes
  PlaneSet planes;
  std::array<FixedPoint, 4> vertex_fixed{};  // 3 triangle vertices (post swap) or 4 line quad corners
  PixelRect bbox;                            // llvmpipe's bounding box, clamped at 0
  PixelRect visit;  // pixels tested: binned area ∩ framebuffer ∩ pixels whose samples the planes reach
  // Multisample rasterization: each sample at its own location. Otherwise the pixel-centre result
  // (and depth) goes to every sample of the pixel.
  bool per_sample = false;
  bool has_depth = false;
  DepthPlane depth;
  DepthOffset offset;
  // Set for a triangle outside the direct range (binned_triangle.hpp, rules §7.5): its coverage is
  // llvmpipe's binned and tiled integer arithmetic, not the plane test; `planes` then only carry
  // the scissor planes' place in `visit`.
  std::shared_ptr<const BinnedTriangle> binned;
};

SamplePoint sample_point(int32_t px, int32_t py, uint32_t sample, bool per_sample);

// The common tail of triangle and line set-up: drop a primitive whose bounding box misses the draw
// region (false), clamp the box at 0, add the scissor planes it needs, and work out the pixels to
// visit from the binned area, the framebuffer and the extent of the primitive's vertices (not for a
// binned triangle, whose wrapping arithmetic may cover samples outside it).
bool place_in_region(RasterPrimitive& primitive, const PixelRect& bbox, const PixelRect& region,
                     const PixelRect& framebuffer, bool multisample, bool binned = false,
                     bool sample_exact_scissor = false);

}  // namespace rastercmp::cpu
