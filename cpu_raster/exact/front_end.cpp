#include "cpu_raster/exact/front_end.hpp"

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/clip_line.hpp"
#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/clip_vertex.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"
#include "cpu_raster/exact/line_setup.hpp"
#include "cpu_raster/exact/pipeline_cull.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu {
namespace {

// The planes a primitive wholly inside is clipped against anyway: none, unless the clip skip is off.
uint32_t inside_planes(const FrameContext& frame, bool depth_clip) {
  return frame.skips.clip_only_when_needed ? 0 : tested_clip_planes(depth_clip);
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
    if (!result.float_culled) record_triangle_setup(result, setup_triangle(result.window, owner, ctx));
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
  const LineSetup setup = setup_line({clipped.line[0].window, clipped.line[1].window},
                                     encode_owner(ctx.draw_index, prim.primitive_index), ctx);
  outcome.reached_setup = true;
  outcome.setup_fate = setup.fate;
  outcome.has_bbox = setup.fate != SetupFate::NonFinite && setup.fate != SetupFate::Degenerate;
  outcome.bbox = setup.bbox;
  outcome.raster = setup.raster;
  sink(outcome);
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

void run_front_end(const FrameContext& frame, uint32_t draw_index, const OutcomeSink& sink) {
  const Draw& draw = frame.scene->draws[draw_index];
  const SetupContext ctx = make_setup_context(frame, draw_index);
  PrimitiveOutcome base;
  base.draw_index = draw_index;
  base.is_line = is_line_topology(draw.topology);
  const std::vector<bool> pipelined = pipelined_chunks(draw, draw.state.depth_clip_enabled());  // §1.5
  const uint32_t count = primitive_count(draw), per_chunk = primitives_per_chunk(draw);
  for (uint32_t i = 0; i < count; ++i) {
    const AssembledPrimitive prim = assemble_primitive(draw, i);
    PrimitiveOutcome outcome = base;
    outcome.primitive_index = i;
    outcome.pipelined = pipelined[i / per_chunk];
    if (base.is_line)
      run_line(frame, ctx, draw, prim, outcome, sink);
    else
      run_triangle(frame, ctx, draw, prim, outcome, sink);
  }
}

}  // namespace rastercmp::cpu
