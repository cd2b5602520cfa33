// Why a sample ended up as it did on the classic path (render_classic.hpp), beside the exact path.
// Two labelled blocks:
//  "method (judged)": the methods chosen per stage, then every primitive that reached the pixel
//    after the clip and cull stages, in the order the visibility stage draws them (submission order
//    for zbuffer, painting order for painter and bsp), each with the method's own decision variables
//    there and the exact rule's decision on the same primitive beside them:
//      clip   line clippers: the clip-space outcodes, Liang–Barsky's per-plane d0, d1, t and
//             t_in / t_out, Cohen–Sutherland's outcodes per pass and the side cut, Cyrus–Beck's
//             per-edge t and t_in / t_out; triangle clippers: the vertex outcodes and the fan;
//      cull   normal_dot_view: each triangle it removed near the pixel with N, V and N·V, beside
//             the exact path's snapped signed area and facing there;
//      fill   the spans on the pixel's row (flood: outline or filled, and the seed), beside the
//             24.8 edge values with the top-left rule;
//      line   dda: the accumulated minor coordinate at the pixel's row or column and its rounding;
//             bresenham: the error term and the step decision there; beside lavapipe's line planes;
//      depth  the method's value (perspective_correct: the barycentrics, 1/w per vertex and at the
//             sample), beside the exact plane's z and raw depth, then the replayed depth test;
//      visibility  painter: the sort keys of the triangles painted at the pixel and their order;
//             bsp: per piece painted there, the path from the root with the viewer's side of each
//             node's plane;
//    and "classic result", what the render holds ("stored before/after" are the render's).
//  "exact (reference)": the exact path's own history of the sample (cpu_raster/exact/explain.hpp,
//    every stage exact), its result, and one line "differ:" naming the owner and raw depth where the
//    two differ.
#pragma once

#include <cstdint>
#include <string>

#include "cpu_raster/exact/cpu_options.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Throws as render_classic does (UsageError, NotSupportedError) and UsageError for a pixel or
// sample outside the framebuffer.
std::string explain_classic_pixel(const Scene& scene, const CpuOptions& options, uint32_t x, uint32_t y,
                                  uint32_t sample = 0);

}  // namespace rastercmp
