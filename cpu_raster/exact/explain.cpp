#include "cpu_raster/exact/explain.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/profile_support.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "model/errors.hpp"
#include "model/render_result.hpp"

namespace rastercmp {
namespace {

using cpu::PrimitiveOutcome;
using cpu::SetupFate;

struct Probe {
  int32_t x, y;
  uint32_t sample, samples;
  std::array<uint32_t, 4> stored;  // the pixel's sample depths as the render holds them at this point
};

CullReason cull_reason(const PrimitiveOutcome& o) {
  if (o.float_culled) return CullReason::FloatCull;
  switch (o.setup_fate) {
    case SetupFate::Rasterized: return CullReason::None;
    case SetupFate::NonFinite: return CullReason::NonFinite;
    case SetupFate::Degenerate: return CullReason::Degenerate;
    case SetupFate::Culled: return CullReason::Facing;
    case SetupFate::OutsideRegion: return CullReason::OutsideRegion;
  }
  return CullReason::None;
}

// Whether a primitive that did not reach the rasterizer came near the pixel.
bool near_pixel(const PrimitiveOutcome& o, const Probe& p) {
  if (o.has_bbox) return o.bbox.contains(p.x, p.y);
  if (!o.float_culled) return false;
  float x0 = o.window[0].x, x1 = x0, y0 = o.window[0].y, y1 = y0;  // float cull: window extent
  for (const cpu::WindowVertex& v : o.window) {
    x0 = std::fmin(x0, v.x), x1 = std::fmax(x1, v.x), y0 = std::fmin(y0, v.y), y1 = std::fmax(y1, v.y);
  }
  return float(p.x) + 1 >= x0 && float(p.x) <= x1 && float(p.y) + 1 >= y0 && float(p.y) <= y1;
}

FragmentRecord base_record(const PrimitiveOutcome& o) {
  FragmentRecord r;
  r.draw_index = o.draw_index;
  r.primitive_index = o.primitive_index;
  r.is_line = o.is_line;
  r.clipped = o.clip_fate == cpu::ClipFate::Clipped;
  r.clip_piece = o.piece;
  r.clip_pieces = o.piece_count;
  r.cull = cull_reason(o);
  r.front_facing = o.front_facing;
  r.fixed_area = o.area;
  r.float_cull_ran = o.float_cull_ran;
  r.float_det = o.float_det;
  return r;
}

void record_planes(FragmentRecord& r, const cpu::RasterPrimitive& raster, const cpu::SampleVerdict& verdict) {
  r.sample_x_fixed = verdict.point.x_fixed;
  r.sample_y_fixed = verdict.point.y_fixed;
  if (raster.binned) return;  // its planes' values do not decide (binned_triangle.hpp)
  r.edge_count = raster.edge_count;
  r.scissor_plane_count = raster.planes.count - raster.edge_count;
  for (uint32_t i = 0; i < raster.planes.count; ++i) {
    const int64_t value = cpu::edge_value(raster.planes.plane[i], verdict.point.x_fixed, verdict.point.y_fixed);
    if (i < raster.edge_count) {
      r.edge_value[i] = value;
      r.edge_inclusive[i] = raster.planes.plane[i].inclusive;
    } else {
      r.scissor_value[i - raster.edge_count] = value;
    }
  }
}

void record_depth(FragmentRecord& r, const cpu::RasterPrimitive& raster, const cpu::SampleVerdict& verdict,
                  const cpu::DepthTestState& depth, const Draw& draw, Probe& probe) {
  r.depth_tested = true;
  r.depth_interpolated = verdict.depth.interpolated;
  r.bias_computed = raster.offset.computed;
  r.bias_m = raster.offset.m;
  r.bias_r = raster.offset.r;
  r.bias_constant_factor = draw.state.depth_bias.constant_factor;
  r.bias_slope_factor = draw.state.depth_bias.slope_factor;
  r.bias_clamp = draw.state.depth_bias.clamp;
  r.bias_clamp_applied = raster.offset.clamped;
  r.bias_offset = raster.offset.offset;
  r.depth_with_offset = verdict.depth.with_offset;
  r.depth_clamped_01 = verdict.depth.clamped_01;
  r.depth_clamp_enabled = depth.range.clamp;
  r.depth_clamped = verdict.depth.depth_clamped;
  r.depth_raw = verdict.depth.raw;
  r.compare_op = depth.op;
  uint32_t& stored = probe.stored[r.depth_sample];
  r.stored_before = stored;
  r.depth_passed = verdict.depth_passed;
  if (verdict.depth_passed && depth.write) stored = verdict.depth.raw;
  r.stored_after = stored;
}

std::optional<FragmentRecord> trace(const PrimitiveOutcome& o, const cpu::DepthTestState& depth, const Draw& draw,
                                    Probe& probe) {
  if (!o.rasterized()) {
    if (!near_pixel(o, probe)) return std::nullopt;
    return base_record(o);
  }
  const cpu::RasterPrimitive& raster = o.raster;
  // Without multisample rasterization the fragment is tested at sample 0 and owns every sample (§6).
  const uint32_t tested = raster.per_sample ? probe.sample : 0;
  const cpu::SampleVerdict verdict =
      cpu::evaluate_sample(raster, depth, probe.x, probe.y, tested, probe.stored[tested]);
  const bool visited = raster.visit.contains(probe.x, probe.y);
  if (!visited && !raster.bbox.contains(probe.x, probe.y) && !verdict.covered()) return std::nullopt;
  FragmentRecord r = base_record(o);
  r.depth_sample = tested;
  r.one_fragment_per_pixel = !raster.per_sample && probe.samples > 1;
  record_planes(r, raster, verdict);
  r.covered = visited && verdict.covered();
  r.failing_plane = verdict.failing_plane;
  r.miss = r.covered ? MissReason::None
           : !verdict.covered()
               ? (uint32_t(verdict.failing_plane) < raster.edge_count ? MissReason::Edge : MissReason::Scissor)
               : MissReason::NotVisited;
  if (r.covered && depth.active) record_depth(r, raster, verdict, depth, draw, probe);
  r.owner_written = r.covered && verdict.depth_passed;
  return r;
}

}  // namespace

std::vector<FragmentRecord> explain_pixel(const Scene& scene, const CpuOptions& options, uint32_t x, uint32_t y,
                                          uint32_t sample) {
  cpu::check_lavapipe_profile_support(scene);
  if (x >= scene.width || y >= scene.height || sample >= scene.samples)
    throw UsageError("explain: pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") sample " +
                     std::to_string(sample) + " is outside the " + std::to_string(scene.width) + "x" +
                     std::to_string(scene.height) + " framebuffer with " + std::to_string(scene.samples) +
                     " sample(s)");
  const cpu::DenormalsFlushed ftz_daz;  // as render_exact (rules §7.10)
  const cpu::FrameContext frame =
      cpu::make_frame_context(scene, options.fma, cpu::parse_setup_methods(options.methods), cpu::WorkSkips{},
                              options.lavapipe->rules());
  Probe probe{int32_t(x), int32_t(y), sample, scene.samples, {}};
  probe.stored.fill(scene.has_depth() ? cpu::clear_depth_raw(scene.depth_format, scene.depth_clear) : 0);
  std::vector<FragmentRecord> records;
  for (uint32_t d = 0; d < scene.draws.size(); ++d) {
    const cpu::DepthTestState depth = cpu::make_depth_test_state(scene, scene.draws[d], frame.viewport, options.fma);
    cpu::run_front_end(frame, d, [&](const PrimitiveOutcome& outcome) {
      if (std::optional<FragmentRecord> r = trace(outcome, depth, scene.draws[d], probe)) records.push_back(*r);
    });
  }
  return records;
}

}  // namespace rastercmp
