// The CPU renderer's spec profile (--profile spec): what the Vulkan specification requires of ANY
// conformant device with `CpuOptions::sub_pixel_bits` of sub-pixel precision, as the three states
// of the CTS rasterization verifier (tcuRasterizationVerifier): every sample of the union of all
// draws is Must, May or MustNot be covered. docs/spec-profile.md describes the rules, their
// sources and the approximations.
//
// Not supported (NotSupportedError, as in the lavapipe profile): point_list, polygon_mode
// line/point, rectangular_smooth lines.
#pragma once

#include <vector>

#include "cpu_raster/exact/cpu_options.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Per sample (RenderResult order), the class of the union of all draws. Throws NotSupportedError,
// InputError (an index past the positions), UsageError (sub_pixel_bits 0).
std::vector<CoverageClass> spec_coverage_classes(const Scene& scene, const CpuOptions& options);

// What the spec profile cannot classify: NotSupportedError (point_list, polygon_mode line/point),
// InputError (an index past the positions). The façade calls it before rendering the estimate.
void check_spec_profile_support(const Scene& scene);

// Vulkan "Controlling the Viewport": "The floating-point viewport bounds are represented with an
// implementation-dependent precision", CpuOptions::viewport_sub_pixel_bits of it. The viewports
// other than the scene's own that a device may hold for it: x, y, width and height each on that
// grid, rounded either way (none when its bounds lie on the grid). The profile judges a render by
// these and the scene's own: Must and MustNot where every one says so, May elsewhere, the hull of
// the depth intervals, every owner alternative.
std::vector<Viewport> spec_viewport_representations(const Scene& scene, const CpuOptions& options);

// backend "cpu", device "cpu spec profile (subPixelPrecisionBits N)", coverage_class from
// spec_coverage_classes. owner and depth_raw are a best estimate: `estimate`, the lavapipe
// profile's render of the same scene with the same fma, threads and methods, which the caller
// makes (render_cpu does; this layer renders nothing itself). Only coverage is judged by class;
// the estimate names owners for wrong-owner warnings and gives depth values.
RenderResult render_spec_profile(const Scene& scene, const CpuOptions& options, RenderResult estimate);

}  // namespace rastercmp
