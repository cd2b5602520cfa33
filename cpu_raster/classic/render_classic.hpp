// The CPU renderer with classic methods selected per stage (--method STAGE=NAME or a scene's
// "methods" object; docs/methods.md "Selecting a method"). Stages it replaces run the modules of
// cpu_raster/methods/; every other stage is the exact path's own function, so with every stage
// at `exact` (visibility `zbuffer`) the result is the exact path's, bit for bit. Owner ids are
// encode_owner(draw, primitive) and depth is stored raw per format, as the exact path does, so the
// output goes through the same compare and report.
#pragma once

#include "cpu_raster/exact/cpu_options.hpp"
#include "model/render_result.hpp"

namespace rastercmp {

// True when options.methods names a classic stage (clip, fill, line, depth, visibility, cull);
// snap and tie_break alone are the exact path's ablations. Does not validate names.
bool uses_classic_methods(const CpuOptions& options);

// Throws UsageError for an unknown stage or name, NotSupportedError for the spec profile, for
// multisampling with a per-pixel method (fill, line, bilinear or perspective_correct depth,
// painter, bsp), for painter/bsp with lines and for dda/bresenham with lines wider than 1 pixel,
// and what the exact path refuses.
RenderResult render_classic(const Scene& scene, const CpuOptions& options);

}  // namespace rastercmp
