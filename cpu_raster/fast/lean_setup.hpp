// The set-up of an unclipped triangle of an exact draw (BandWorker::walk_exact: multisampled
// frames, draws the fast walk leaves to the exact front end), lean: setup_triangle's steps for a
// triangle whose corners snap and whose edges stay in the direct range, written into a
// RasterPrimitive the worker keeps from triangle to triangle instead of a TriangleSetup formed
// and copied, each corner coordinate snapped by one SSE rounding.
#pragma once

#include <array>
#include <cstdint>

#include "cpu_raster/exact/raster_primitive.hpp"
#include "cpu_raster/exact/setup_context.hpp"
#include "cpu_raster/exact/viewport.hpp"

namespace rastercmp::cpu::fast {

enum class LeanSetup {
  Drawn,    // `out` holds what setup_triangle's raster holds, ready for the rasterizer
  Dropped,  // setup_triangle's fate is Degenerate, Culled or OutsideRegion: nothing to draw
  Full,     // a corner does not snap, an edge leaves the direct range, or the snap rounding is not
            // nearest-even: setup_triangle decides (and may take llvmpipe's wrapping set-up)
};

// Call with denormals flushed (the set-up's mode here) on a host with SSE4.1 (AVX2 hosts).
LeanSetup setup_triangle_lean(const std::array<WindowVertex, 3>& window, uint32_t owner, const SetupContext& ctx,
                              RasterPrimitive& out);

}  // namespace rastercmp::cpu::fast
