// Triangle fill by edge functions evaluated in float at pixel centres, without sub-pixel snapping
// — the common textbook shortcut (tinyrenderer's barycentric test; the "Rasterizing a Triangle"
// slide of lecture-rasterization-depth-sorting-culling.txt is the scanline form of it).
//
// E_ab(p) = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x), in float32, each operation
// rounded on its own (-ffp-contract=off, no std::fma). The vertices are reordered so that the
// interior is E > 0 on all three edges; a zero-area triangle covers nothing.
// Pixel (x, y) is sampled at its centre (x + 0.5f, y + 0.5f) in window coordinates (y down).
//
//   EdgeTieRule::None    covered iff E >= 0 on every edge: no tie rule, so a pixel centre on an
//                        edge shared by two triangles is filled by both (double fill).
//   EdgeTieRule::TopLeft covered iff E > 0, or E == 0 on a top or left edge (y down: a left edge
//                        has the interior to its right, dE/dx > 0; a top edge is horizontal with
//                        the interior below, dE/dx == 0 and dE/dy > 0) — the D3D/Vulkan rule that
//                        lavapipe applies in fixed point (docs/lavapipe-rules.md §2.4).
//
// Does not: snap to fixed point, so E == 0 is only reliable when E is computed exactly (small
//       coordinates on a coarse grid); the two triangles of a shared edge compute E from different
//       vertices and may round differently. Does not interpolate depth or attributes.
#pragma once

#include <array>
#include <vector>

#include "cpu_raster/methods/spans.hpp"

namespace rastercmp::methods {

struct Vec2f {
  float x = 0, y = 0;
};

enum class EdgeTieRule { None, TopLeft };

// Spans of the pixels covered inside the triangle's bounding box, clamped to `bounds`. Every pixel
// of that box is tested, so pass the framebuffer as `bounds`; pixel centres are exact floats for
// |x|, |y| < 2^22.
std::vector<Span> fill_triangle_edge_function(const std::array<Vec2f, 3>& pos_window, EdgeTieRule tie_rule,
                                              const PixelBounds& bounds = {});

// The float edge function itself (exposed for tests and for the pipeline's comparisons).
float edge_function(Vec2f a, Vec2f b, Vec2f p);

}  // namespace rastercmp::methods
