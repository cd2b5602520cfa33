// The CPU renderer: an independent pipeline that reproduces lavapipe (profile Lavapipe) or
// follows only what the Vulkan specification requires (profile Spec). See docs/cpu-raster.md.
//
// This is the façade: the one header the rest of the project includes. It picks the layer that
// renders (cpu_raster/render_cpu.cpp); the layers below it (exact/, fast/, spec/, classic/,
// methods/) never include it.
#pragma once

#include <string>
#include <vector>

#include "cpu_raster/classic/method_registry.hpp"  // the stages and methods --method accepts
#include "cpu_raster/exact/cpu_options.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Renders a scene. Throws NotSupportedError for state the profile cannot reproduce.
RenderResult render_cpu(const Scene& scene, const CpuOptions& options);

// Spec profile: the owner one exactly computing device leaves at a sample, and its choices in
// words (docs/spec-profile.md "Owners", cpu_raster/spec/exact_owners.hpp).
struct ExactDeviceOwner {
  std::string device;  // e.g. "floor vertex rounding, top-left tie rule"
  uint32_t owner = kOwnerBackground;
};

// Every simulated exact device's owner of sample (x, y, sample), for `rastercmp explain`; empty
// where the profile simulates none (undefined primitives). Lines are not simulated. Throws NotSupportedError for
// a scene the spec profile does not support.
std::vector<ExactDeviceOwner> exact_device_owners_at(const Scene& scene, const CpuOptions& options, uint32_t x,
                                                     uint32_t y, uint32_t sample);

// Spec profile: why a pixel has its class, for `rastercmp explain` (docs/spec-profile.md). For the
// scene's own viewport; `viewports` counts the other representations of its bounds that were judged.
struct SpecPixelRules {
  struct Primitive {
    uint32_t owner = kOwnerBackground;
    bool line = false;
    std::string coverage;  // "full", "partial" or "none": the primitive's own class at the pixel
    std::string gate;      // "certain", "maybe" or "never": culling and the test against the clear value
  };
  std::vector<Primitive> primitives;  // every primitive whose reach holds the pixel, in submission order
  bool in_scissor = true;
  bool undefined = false;  // a primitive with undefined coordinates: May inside the scissor
  bool owner_open = false;
  std::string open_reason;  // why the owner is open (cpu_raster/spec/open_owners.hpp)
  size_t viewports = 0;
};
SpecPixelRules spec_pixel_rules(const Scene& scene, const CpuOptions& options, const RenderResult& expected, uint32_t x,
                                uint32_t y);

// Checks one STAGE=NAME choice against the stages and names the CPU renderer knows (the classic
// path's tables and the exact path's snap / tie_break). Returns "" when it is known, else what is
// wrong and the accepted names, e.g. `unknown name "x" for stage "fill"; known: exact, scanline, ...`.
std::string method_choice_problem(const MethodChoice& choice);

// The most CPU worker threads --threads accepts (docs/reliability.md).
inline constexpr unsigned kMaxCpuThreads = 256;

}  // namespace rastercmp
