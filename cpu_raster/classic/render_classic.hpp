// The CPU renderer with classic methods selected per stage (--method STAGE=NAME or a scene's
// "methods" object; docs/methods.md "Selecting a method"). Stages it replaces run the modules of
// cpu_raster/methods/; every other stage is the exact path's own function, so with every stage
// at `exact` (visibility `zbuffer`) the result is the exact path's, bit for bit. Owner ids are
// encode_owner(draw, primitive) and depth is stored raw per format, as the exact path does, so the
// output goes through the same compare and report.
#pragma once

#include <vector>

#include "cpu_raster/classic/classic_front_end.hpp"
#include "cpu_raster/exact/cpu_options.hpp"
#include "model/render_result.hpp"

namespace rastercmp {

namespace cpu::classic {

// What render_classic draws: the parsed methods, the frame and the primitives that reach the
// fill, line, depth and visibility stages; with `keep_culled` (explain) also the triangles
// cull=normal_dot_view removed. Throws as render_classic.
struct ClassicFrame {
  ClassicMethods chosen;
  FrameContext frame;
  std::vector<ClassicPrimitive> primitives;
  std::vector<CulledTriangle> culled;
};
ClassicFrame prepare_classic_frame(const Scene& scene, const CpuOptions& options, bool keep_culled = false);

}  // namespace cpu::classic

// True when options.methods names a classic stage (clip, fill, line, depth, visibility, cull);
// snap and tie_break alone are the exact path's ablations. Does not validate names.
bool uses_classic_methods(const CpuOptions& options);

// Throws UsageError for an unknown stage or name, NotSupportedError for the spec profile, for a
// method the scene does not suit (method_inapplicable, method_registry.hpp: multisampling with a
// per-pixel method, painter/bsp with lines, dda/bresenham with wide lines, a 2-D clipper with
// vertices behind the eye or beyond the depth planes, pseudo-depth with w outside near..far) and
// what the exact path refuses.
RenderResult render_classic(const Scene& scene, const CpuOptions& options);

}  // namespace rastercmp
