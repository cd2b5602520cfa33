// The CPU renderer: an independent pipeline that reproduces lavapipe (profile Lavapipe) or
// follows only what the Vulkan specification requires (profile Spec). See docs/cpu-raster.md.
//
// This is the façade: the one header the rest of the project includes. It picks the layer that
// renders (cpu_raster/render_cpu.cpp); the layers below it (exact/, fast/, spec/, classic/,
// methods/) never include it.
#pragma once

#include <string>

#include "cpu_raster/classic/method_registry.hpp"  // the stages and methods --method accepts
#include "cpu_raster/exact/cpu_options.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Renders a scene. Throws NotSupportedError for state the profile cannot reproduce.
RenderResult render_cpu(const Scene& scene, const CpuOptions& options);

// Checks one STAGE=NAME choice against the stages and names the CPU renderer knows (the classic
// path's tables and the exact path's snap / tie_break). Returns "" when it is known, else what is
// wrong and the accepted names, e.g. `unknown name "x" for stage "fill"; known: exact, scanline, ...`.
std::string method_choice_problem(const MethodChoice& choice);

// The most CPU worker threads --threads accepts (docs/reliability.md).
inline constexpr unsigned kMaxCpuThreads = 256;

}  // namespace rastercmp
