// The set-ups of an exact draw's primitives (BandWorker::walk_exact: lines, multisampled frames,
// draws the fast walk leaves to the exact front end), lean: setup_triangle's steps for an
// unclipped triangle, setup_line's for a rectangular line, when the corners snap and the edges
// stay in the direct range, written into a RasterPrimitive the worker keeps from primitive to
// primitive instead of a TriangleSetup or LineSetup formed and copied, each coordinate snapped by
// one SSE rounding.
#pragma once

#include <array>
#include <cstdint>

#include "cpu_raster/exact/raster_primitive.hpp"
#include "cpu_raster/exact/setup_context.hpp"
#include "cpu_raster/exact/viewport.hpp"

namespace rastercmp::cpu::fast {

enum class LeanSetup {
  Drawn,    // `out` holds what the full set-up's raster holds, ready for the rasterizer
  Dropped,  // the full set-up's fate is Degenerate, Culled or OutsideRegion: nothing to draw
  Full,     // a corner does not snap, an edge leaves the direct range, or (triangles) the snap
            // rounding is not nearest-even, (lines) the line is a Bresenham one: the full set-up
            // decides (and may take llvmpipe's wrapping set-up)
};

// Call with denormals flushed (the set-up's mode here) on a host with SSE4.1 (AVX2 hosts).
LeanSetup setup_triangle_lean(const std::array<WindowVertex, 3>& window, uint32_t owner, const SetupContext& ctx,
                              RasterPrimitive& out);

// setup_line's rectangular quad (DEFAULT and RECTANGULAR lines: lp_setup_line.c try_setup_line,
// lavapipe-rules §5.3, §8.1): the same conditions and host as above.
LeanSetup setup_line_lean(const std::array<WindowVertex, 2>& window, uint32_t owner, const SetupContext& ctx,
                          RasterPrimitive& out);

}  // namespace rastercmp::cpu::fast
