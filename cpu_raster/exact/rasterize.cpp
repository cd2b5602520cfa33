#include "cpu_raster/exact/rasterize.hpp"

#include <optional>

namespace rastercmp::cpu {

DepthTestState make_depth_test_state(const Scene& scene, const Draw& draw, const ViewportTransform& viewport, bool fma,
                                     const WorkSkips& skips) {
  DepthTestState state;
  state.active = scene.has_depth() && draw.state.depth.test_enable;
  state.write = state.active && draw.state.depth.write_enable;
  state.op = draw.state.depth.compare_op;
  state.format = scene.depth_format;
  state.range = DepthRange{draw.state.depth_clamp, viewport.zmin, viewport.zmax};
  state.fma = fma;
  state.compute_when_inactive = !skips.depth_only_when_attached;
  return state;
}

SampleVerdict evaluate_sample(const RasterPrimitive& p, const DepthTestState& depth, int32_t px, int32_t py,
                              uint32_t sample, uint32_t stored_raw, const EdgeFrame32* frame32) {
  SampleVerdict verdict;
  // Without multisample rasterization every sample takes the pixel-centre result.
  verdict.point = sample_point(px, py, p.per_sample ? sample : 0, p.per_sample);
  if (p.binned) {
    verdict.failing_plane = binned_covers(*p.binned, px, py, p.per_sample ? sample : 0) ? -1 : 0;
  } else {
    verdict.failing_plane = frame32
                                ? first_failing_plane32(*frame32, int32_t(verdict.point.x_fixed - frame32->x0_fixed),
                                                        int32_t(verdict.point.y_fixed - frame32->y0_fixed))
                                : first_failing_plane(p.planes, verdict.point.x_fixed, verdict.point.y_fixed);
  }
  if (!verdict.covered() || !(depth.active || depth.compute_when_inactive)) return verdict;
  verdict.depth =
      sample_depth(p.depth, p.offset.offset, verdict.point.x, verdict.point.y, depth.range, depth.format, depth.fma);
  if (depth.active) {
    verdict.depth_passed = depth_test_passes(depth.op, depth.format, verdict.depth.raw, stored_raw);
  } else if (depth.format != DepthFormat::None) {  // the depth skip is off: compared, and discarded
    const bool discarded = depth_test_passes(depth.op, depth.format, verdict.depth.raw, stored_raw);
    (void)discarded;
  }
  return verdict;
}

SampleVerdict evaluate_sample(const RasterPrimitive& p, const DepthTestState& depth, int32_t px, int32_t py,
                              uint32_t sample, uint32_t stored_raw) {
  return evaluate_sample(p, depth, px, py, sample, stored_raw, nullptr);
}

void rasterize_primitive(const RasterPrimitive& p, const DepthTestState& depth, RenderTargets& targets,
                         const WorkSkips& skips) {
  const std::optional<EdgeFrame32> frame32 =
      skips.edges32_when_box_fits && !p.binned ? make_edge_frame32(p.planes, p.visit) : std::nullopt;
  const EdgeFrame32* edges32 = frame32 ? &*frame32 : nullptr;
  const bool read_stored = (depth.active || depth.compute_when_inactive) && !targets.depth_raw.empty();
  // A primitive rasterized without multisampling in a multisampled framebuffer (a Bresenham line)
  // makes one fragment per pixel: tested against sample 0's depth, its depth written to sample 0
  // only, its owner to every sample (docs/lavapipe-rules.md §6).
  const uint32_t tested_samples = p.per_sample ? targets.samples : 1;
  for (int32_t py = p.visit.y0; py <= p.visit.y1; ++py) {
    for (int32_t px = p.visit.x0; px <= p.visit.x1; ++px) {
      for (uint32_t s = 0; s < tested_samples; ++s) {
        const size_t i = targets.index(px, py, s);
        const SampleVerdict verdict =
            evaluate_sample(p, depth, px, py, s, read_stored ? targets.depth_raw[i] : 0, edges32);
        if (!verdict.passes()) continue;
        if (depth.write) targets.depth_raw[i] = verdict.depth.raw;
        if (p.per_sample) {
          targets.owner[i] = p.owner;
        } else {
          for (uint32_t t = 0; t < targets.samples; ++t) targets.owner[targets.index(px, py, t)] = p.owner;
        }
      }
    }
  }
}

}  // namespace rastercmp::cpu
