// render_exact: the exact path, in the order of the specification's chapters.
#include "cpu_raster/exact/render_exact.hpp"

#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/profile_support.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "cpu_raster/exact/render_targets.hpp"

namespace rastercmp {

// For each draw, the geometry stages (assemble, clip test, clip, viewport, set-up:
// cpu::run_front_end), then rasterization, the depth test and the writes
// (cpu::rasterize_primitive). options.skips: cpu_raster/exact/work_skips.hpp.
RenderResult render_exact(const Scene& scene, const CpuOptions& options) {
  cpu::check_lavapipe_profile_support(scene);
  const cpu::DenormalsFlushed ftz_daz;  // draw_vbo and the rasterizer threads (rules §7.10)
  const cpu::FrameContext frame =
      cpu::make_frame_context(scene, options.fma, cpu::parse_setup_methods(options.methods), options.skips,
                                options.lavapipe->rules());
  cpu::RenderTargets targets = cpu::make_render_targets(scene);
  for (uint32_t d = 0; d < scene.draws.size(); ++d) {
    const cpu::DepthTestState depth =
        cpu::make_depth_test_state(scene, scene.draws[d], frame.viewport, options.fma, options.skips);
    cpu::run_front_end(frame, d, [&](const cpu::PrimitiveOutcome& outcome) {
      if (outcome.rasterized()) cpu::rasterize_primitive(outcome.raster, depth, targets, options.skips);
    });
  }
  RenderResult result;
  cpu::move_into_result(std::move(targets), lavapipe_profile_device(options), options.fma, result);
  return result;
}

}  // namespace rastercmp
