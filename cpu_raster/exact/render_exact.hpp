// The exact path's entry point: the scalar pipeline that reproduces lavapipe bit for bit
// (docs/cpu-raster.md). The fast, spec and classic layers call it; it calls none of them.
#pragma once

#include "cpu_raster/exact/cpu_options.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Renders a scene on the exact path (profile Lavapipe; options.threads and options.profile are
// not read; options.methods may name only set-up methods). Throws NotSupportedError for state
// the profile cannot reproduce.
RenderResult render_exact(const Scene& scene, const CpuOptions& options);

}  // namespace rastercmp
