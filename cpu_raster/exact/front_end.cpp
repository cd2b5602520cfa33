#include "cpu_raster/exact/front_end.hpp"

#include <algorithm>

#include <fmt/core.h>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/clip_line.hpp"
#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/clip_vertex.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/line_setup.hpp"
#include "cpu_raster/exact/pipeline_cull.hpp"
#include "model/errors.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu {
namespace {

// The planes a primitive wholly inside is clipped against anyway: none, unless the clip skip is off.
uint32_t inside_planes(const FrameContext& frame, bool depth_clip) {
  return frame.skips.clip_only_when_needed ? 0 : tested_clip_planes(depth_clip);
}

// A float as the rasterizer threads read it: under DAZ a denormal is a zero of its sign (§7.10).
uint32_t bits_as_read(float value) {
  const uint32_t bits = float_bits(value);
  return (bits & 0x7f800000u) == 0 ? (bits & 0x80000000u) : bits;
}

bool same_as_read(const DepthPlane& a, const DepthPlane& b) {
  return bits_as_read(a.a0) == bits_as_read(b.a0) && bits_as_read(a.dzdx) == bits_as_read(b.dzdx) &&
         bits_as_read(a.dzdy) == bits_as_read(b.dzdy);
}

bool same_planes(const PlaneSet& a, const PlaneSet& b) {
  if (a.count != b.count) return false;
  for (uint32_t k = 0; k < a.count; ++k) {
    const EdgePlane &p = a.plane[k], &q = b.plane[k];
    if (p.c != q.c || p.dcdx != q.dcdx || p.dcdy != q.dcdy) return false;
  }
  return true;
}

// Whether two set-ups of one primitive rasterize alike (what the rasterizer reads of them).
bool same_rasterization(SetupFate fate_a, const RasterPrimitive& a, SetupFate fate_b, const RasterPrimitive& b) {
  if (fate_a != fate_b) return false;
  if (fate_a != SetupFate::Rasterized) return true;
  bool same = a.edge_count == b.edge_count && same_planes(a.planes, b.planes) && a.bbox == b.bbox &&
              a.visit == b.visit && a.has_depth == b.has_depth && (a.binned == nullptr) == (b.binned == nullptr);
  for (size_t k = 0; k < a.vertex_fixed.size() && same; ++k)
    same = a.vertex_fixed[k].x.raw == b.vertex_fixed[k].x.raw && a.vertex_fixed[k].y.raw == b.vertex_fixed[k].y.raw;
  return same && same_as_read(a.depth, b.depth) && bits_as_read(a.offset.offset) == bits_as_read(b.offset.offset);
}

void record_triangle_setup(PrimitiveOutcome& outcome, const TriangleSetup& setup) {
  outcome.reached_setup = true;
  outcome.setup_fate = setup.fate;
  outcome.front_facing = setup.front_facing;
  outcome.area = setup.area;
  outcome.swapped = setup.swapped;
  outcome.has_bbox = setup.fate != SetupFate::NonFinite;
  outcome.bbox = setup.bbox;
  outcome.raster = setup.raster;
}

void run_triangle(const FrameContext& frame, const SetupContext& ctx, const Draw& draw, const AssembledPrimitive& prim,
                  PrimitiveOutcome outcome, const OutcomeSink& sink) {
  const bool depth_clip = draw.state.depth_clip_enabled();
  std::array<ClipVertex, 3> triangle;
  for (size_t k = 0; k < 3; ++k)
    triangle[k] = make_clip_vertex(draw.positions_clip[prim.position[k]], frame.viewport, depth_clip, frame.fma);
  const ClippedTriangles clipped = clip_triangle(triangle, frame.viewport, inside_planes(frame, depth_clip));
  outcome.clip_fate = clipped.fate;
  outcome.piece_count = uint32_t(clipped.triangles.size());
  if (clipped.triangles.empty()) {
    sink(outcome);
    return;
  }
  const uint32_t owner = encode_owner(ctx.draw_index, prim.primitive_index);
  for (uint32_t piece = 0; piece < outcome.piece_count; ++piece) {
    PrimitiveOutcome result = outcome;
    result.piece = piece;
    for (size_t k = 0; k < 3; ++k) result.window[k] = clipped.triangles[piece][k].window;
    if (outcome.pipelined && draw.state.cull_mode != CullMode::None) {  // draw_pipe_cull.c (§2.6)
      result.float_cull_ran = true;
      result.float_det = pipeline_cull_determinant(result.window);
      result.float_culled = pipeline_cull_drops(result.float_det, draw.state.cull_mode, draw.state.front_face);
    }
    if (!result.float_culled)
      record_triangle_setup(result, setup_triangle_in_mode(outcome.setup_denormals, result.window, owner, ctx,
                                                           prim.primitive_index));
    sink(result);
  }
}

void run_line(const FrameContext& frame, const SetupContext& ctx, const Draw& draw, const AssembledPrimitive& prim,
              PrimitiveOutcome outcome, const OutcomeSink& sink) {
  const bool depth_clip = draw.state.depth_clip_enabled();
  std::array<ClipVertex, 2> line;
  for (size_t k = 0; k < 2; ++k)
    line[k] = make_clip_vertex(draw.positions_clip[prim.position[k]], frame.viewport, depth_clip, frame.fma);
  const LineXyClip xy = frame.rules.has(LavapipeRule::LineGuardBand) ? LineXyClip::GuardBand : LineXyClip::Clip;
  const ClippedLine clipped = clip_line(line, frame.viewport, inside_planes(frame, depth_clip), xy);
  outcome.clip_fate = clipped.fate;
  if (clipped.fate == ClipFate::Outside || clipped.fate == ClipFate::Discarded) {
    sink(outcome);
    return;
  }
  outcome.piece_count = 1;
  outcome.window = {clipped.line[0].window, clipped.line[1].window, WindowVertex{}};
  const LineSetup setup =
      setup_line_in_mode(outcome.setup_denormals, {clipped.line[0].window, clipped.line[1].window},
                         encode_owner(ctx.draw_index, prim.primitive_index), ctx, prim.primitive_index);
  outcome.reached_setup = true;
  outcome.setup_fate = setup.fate;
  outcome.has_bbox = setup.fate != SetupFate::NonFinite && setup.fate != SetupFate::Degenerate;
  outcome.bbox = setup.bbox;
  outcome.raster = setup.raster;
  sink(outcome);
}

// Runs `setup` (a callable returning TriangleSetup or LineSetup) in the mode lavapipe sets the
// primitive up in (SetupDenormals, front_end.hpp). Under FTZ|DAZ first, watched: when no
// intermediate was denormal or tiny and no input denormal, the mode cannot matter (DenormalWatch).
template <class Setup>
auto setup_in_mode(SetupDenormals mode, uint32_t draw_index, uint32_t primitive_index, const RasterState& state,
                   Setup setup) {
  if (mode == SetupDenormals::Flushed) {
    const DenormalsFlushed ftz_daz;
    return setup();
  }
  DenormalWatch watch;
  const auto flushed = [&] {
    const DenormalsFlushed ftz_daz;
    return setup();
  }();
  if (!watch.met() && !depth_bias_is_denormal(state.depth_bias)) return flushed;
  const auto kept = [&] {
    const DenormalsKept kept_mode;
    return setup();
  }();
  if (mode == SetupDenormals::Kept) return kept;
  if (!same_rasterization(kept.fate, kept.raster, flushed.fate, flushed.raster))
    throw NotSupportedError(fmt::format(
        "draw {} primitive {}: its set-up gives a different result with denormals flushed and kept, and "
        "lavapipe's draw pipeline sets up this draw's clipped primitives in vertex-buffer batches, only "
        "the last of them outside its denormal mode, whose boundaries the lavapipe profile does not model "
        "(docs/lavapipe-rules.md §7.11)",
        draw_index, primitive_index));
  return kept;
}

}  // namespace

FrameContext make_frame_context(const Scene& scene, bool fma, const SetupMethods& methods, const WorkSkips& skips,
                                const LavapipeRules& rules) {
  FrameContext frame;
  frame.scene = &scene;
  frame.viewport = make_viewport_transform(scene.effective_viewport());
  frame.framebuffer = PixelRect{0, 0, int32_t(scene.width) - 1, int32_t(scene.height) - 1};
  frame.region = draw_region(scene, frame.viewport);
  frame.multisample = scene.samples > 1;
  frame.fma = fma;
  frame.methods = methods;
  frame.skips = skips;
  frame.rules = rules;
  return frame;
}

SetupContext make_setup_context(const FrameContext& frame, uint32_t draw_index) {
  SetupContext ctx;
  ctx.framebuffer = frame.framebuffer;
  ctx.region = frame.region;
  ctx.multisample = frame.multisample;
  ctx.fma = frame.fma;
  ctx.methods = frame.methods;
  ctx.skips = frame.skips;
  ctx.rules = frame.rules;
  ctx.depth_format = frame.scene->depth_format;
  ctx.state = &frame.scene->draws[draw_index].state;
  ctx.draw_index = draw_index;
  return ctx;
}

TrailingPipelineRun trailing_pipeline_run(const Draw& draw, const std::vector<bool>& pipelined) {
  const bool depth_clip = draw.state.depth_clip_enabled();
  return trailing_pipeline_run_of(draw, pipelined, [&](uint32_t position) {
    return clip_mask(draw.positions_clip[position], depth_clip) != 0;
  });
}

SetupDenormals setup_denormals(const TrailingPipelineRun& run, bool pipelined, uint32_t primitive) {
  if (!pipelined || primitive < run.first) return SetupDenormals::Flushed;
  return run.fits_one_batch ? SetupDenormals::Kept : SetupDenormals::EitherMustAgree;
}

TriangleSetup setup_triangle_in_mode(SetupDenormals mode, const std::array<WindowVertex, 3>& window, uint32_t owner,
                                     const SetupContext& ctx, uint32_t primitive_index) {
  return setup_in_mode(mode, ctx.draw_index, primitive_index, *ctx.state,
                       [&] { return setup_triangle(window, owner, ctx); });
}

bool depth_bias_is_denormal(const DepthBias& bias) {
  return is_denormal(bias.constant_factor) || is_denormal(bias.slope_factor) || is_denormal(bias.clamp);
}

LineSetup setup_line_in_mode(SetupDenormals mode, const std::array<WindowVertex, 2>& window, uint32_t owner,
                             const SetupContext& ctx, uint32_t primitive_index) {
  return setup_in_mode(mode, ctx.draw_index, primitive_index, *ctx.state, [&] { return setup_line(window, owner, ctx); });
}

DrawWalk begin_draw(const FrameContext& frame, uint32_t draw_index) {
  const Draw& draw = frame.scene->draws[draw_index];
  std::vector<bool> pipelined = pipelined_chunks(draw, draw.state.depth_clip_enabled());  // §1.5
  const TrailingPipelineRun run = trailing_pipeline_run(draw, pipelined);                 // §7.11
  return begin_draw(frame, draw_index, std::move(pipelined), run);
}

DrawWalk begin_draw(const FrameContext& frame, uint32_t draw_index, std::vector<bool> pipelined,
                    const TrailingPipelineRun& run) {
  const Draw& draw = frame.scene->draws[draw_index];
  DrawWalk walk;
  walk.draw = &draw;
  walk.ctx = make_setup_context(frame, draw_index);
  walk.base.draw_index = draw_index;
  walk.base.is_line = is_line_topology(draw.topology);
  walk.pipelined = std::move(pipelined);
  walk.run = run;
  walk.count = primitive_count(draw);
  walk.per_chunk = primitives_per_chunk(draw);
  return walk;
}

SetupDenormals primitive_setup_denormals(const DrawWalk& walk, uint32_t primitive) {
  return setup_denormals(walk.run, walk.pipelined[primitive / walk.per_chunk], primitive);
}

void run_primitive(const FrameContext& frame, const DrawWalk& walk, uint32_t i, const OutcomeSink& sink) {
  const AssembledPrimitive prim = assemble_primitive(*walk.draw, i);
  PrimitiveOutcome outcome = walk.base;
  outcome.primitive_index = i;
  outcome.pipelined = walk.pipelined[i / walk.per_chunk];
  outcome.setup_denormals = setup_denormals(walk.run, outcome.pipelined, i);
  if (walk.base.is_line)
    run_line(frame, walk.ctx, *walk.draw, prim, outcome, sink);
  else
    run_triangle(frame, walk.ctx, *walk.draw, prim, outcome, sink);
}

void run_front_end(const FrameContext& frame, uint32_t draw_index, const OutcomeSink& sink) {
  const DrawWalk walk = begin_draw(frame, draw_index);
  for (uint32_t i = 0; i < walk.count; ++i) run_primitive(frame, walk, i, sink);
}

}  // namespace rastercmp::cpu
