// The CPU renderer: an independent pipeline that reproduces lavapipe (profile Lavapipe) or
// follows only what the Vulkan specification requires (profile Spec). See docs/cpu-raster.md.
//
// This is the façade: the one header the rest of the project includes. It picks the layer that
// renders (cpu_raster/render_cpu.cpp); the layers below it (exact/, fast/, spec/, classic/,
// methods/) never include it.
#pragma once

#include "cpu_raster/classic/method_registry.hpp"  // the stages and methods --method accepts
#include "cpu_raster/exact/cpu_options.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Renders a scene. Throws NotSupportedError for state the profile cannot reproduce.
RenderResult render_cpu(const Scene& scene, const CpuOptions& options);

}  // namespace rastercmp
