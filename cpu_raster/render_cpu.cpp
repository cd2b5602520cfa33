// render_cpu: the CPU renderer's entry point (cpu_raster/cpu_raster.hpp). It runs the exact path
// below, or hands the scene to the classic-methods path, the spec profile or the fast path.
#include <string>

#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/fast/render_fast.hpp"
#include "cpu_raster/front_end.hpp"
#include "cpu_raster/profile_support.hpp"
#include "cpu_raster/rasterize.hpp"
#include "cpu_raster/render_targets.hpp"
#include "cpu_raster/spec/spec_profile.hpp"

namespace rastercmp {
namespace {

// The exact path, in the order of the specification's chapters: for each draw, the geometry
// stages (assemble, clip test, clip, viewport, set-up: cpu::run_front_end), then rasterization,
// the depth test and the writes (cpu::rasterize_primitive). options.skips: cpu_raster/work_skips.hpp.
RenderResult render_lavapipe(const Scene& scene, const CpuOptions& options) {
  cpu::check_lavapipe_profile_support(scene);
  const cpu::FrameContext frame =
      cpu::make_frame_context(scene, options.fma, cpu::parse_setup_methods(options.methods), options.skips);
  cpu::RenderTargets targets = cpu::make_render_targets(scene);
  for (uint32_t d = 0; d < scene.draws.size(); ++d) {
    const cpu::DepthTestState depth =
        cpu::make_depth_test_state(scene, scene.draws[d], frame.viewport, options.fma, options.skips);
    cpu::run_front_end(frame, d, [&](const cpu::PrimitiveOutcome& outcome) {
      if (outcome.rasterized()) cpu::rasterize_primitive(outcome.raster, depth, targets, options.skips);
    });
  }
  RenderResult result;
  cpu::move_into_result(std::move(targets), kLavapipeProfileDevice, options.fma, result);
  return result;
}

}  // namespace

RenderResult render_cpu(const Scene& scene, const CpuOptions& options) {
  if (uses_classic_methods(options)) return render_classic(scene, options);            // cpu_raster/classic/
  if (options.profile == CpuProfile::Spec) return render_spec_profile(scene, options);  // cpu_raster/spec/
  if (options.threads >= 1) return render_cpu_fast(scene, options);                     // cpu_raster/fast/
  return render_lavapipe(scene, options);
}

}  // namespace rastercmp
