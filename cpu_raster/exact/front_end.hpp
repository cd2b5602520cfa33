// The geometry half of the exact path, per draw: assemble → clip test → clip → viewport →
// pipeline float cull → set-up. Each primitive reports one outcome per piece that reached set-up
// (a clipped triangle can become several), or one outcome saying why nothing did. The renderer
// rasterizes the outcomes; explain inspects them. Both call this same function.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/clip_triangle.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"
#include "cpu_raster/exact/line_setup.hpp"
#include "cpu_raster/exact/raster_primitive.hpp"
#include "cpu_raster/exact/setup_context.hpp"
#include "cpu_raster/exact/triangle_setup.hpp"
#include "cpu_raster/exact/viewport.hpp"
#include "cpu_raster/exact/work_skips.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

// Per render: what every draw shares.
struct FrameContext {
  const Scene* scene = nullptr;
  ViewportTransform viewport;
  PixelRect framebuffer;
  PixelRect region;
  bool multisample = false;
  bool fma = true;
  SetupMethods methods;
  WorkSkips skips;
  LavapipeRules rules;  // the modelled release's (model/lavapipe_release.hpp); empty: 22.3.6
};

FrameContext make_frame_context(const Scene& scene, bool fma, const SetupMethods& methods,
                                const WorkSkips& skips = WorkSkips{}, const LavapipeRules& rules = LavapipeRules{});

// The denormal mode a primitive's set-up (snap, depth plane, offset) runs in (docs/lavapipe-rules.md
// §7.11). llvmpipe's draw_vbo sets FTZ|DAZ; a chunk without clipping is set up inside it, but the
// draw pipeline's primitives wait in the vertex buffer (draw_pipe_vbuf.c) and are set up when it is
// flushed: when it is full or the next chunk without clipping is emitted (inside draw_vbo), or by
// llvmpipe_draw_vbo's draw_flush after draw_vbo has restored the caller's mode (denormals kept).
enum class SetupDenormals {
  Flushed,          // not pipelined, or pipelined before a chunk without clipping
  Kept,             // the draw's trailing pipelined run, which fits one vertex buffer
  EitherMustAgree,  // the trailing run spans vertex buffers whose boundaries are not modelled:
                    // both modes are computed and must rasterize alike, else NotSupportedError
};

// The pipelined chunks at the end of a draw (after its last chunk without clipping), and whether
// their primitives certainly fit one vertex buffer batch.
struct TrailingPipelineRun {
  uint32_t first = 0;  // first primitive of the run; primitive_count(draw) when there is none
  bool fits_one_batch = true;
};
// A batch of the vertex buffer held 43 unclipped triangles (129 vertices) in every measurement
// (docs/lavapipe-rules.md §7.11); a clipped triangle is counted at its worst, 7 fan triangles of
// 3 vertices each.
inline constexpr uint64_t kVbufBatchVertices = 129;
inline constexpr uint64_t kClippedTriangleVertices = 21;
// The run from the chunk flags; `is_clipped(position)`: the vertex has a clip-mask bit (counted
// when the run is not known to fit one batch is all that needs it).
template <class IsClipped>
TrailingPipelineRun trailing_pipeline_run_of(const Draw& draw, const std::vector<bool>& pipelined,
                                             IsClipped is_clipped) {
  const uint32_t count = primitive_count(draw), per_chunk = primitives_per_chunk(draw);
  TrailingPipelineRun run;
  uint32_t chunk = uint32_t(pipelined.size());
  while (chunk > 0 && pipelined[chunk - 1]) --chunk;
  run.first = std::min(count, chunk * per_chunk);
  const bool lines = is_line_topology(draw.topology);
  uint64_t vertices = 0;
  for (uint32_t i = run.first; i < count && vertices <= kVbufBatchVertices; ++i) {
    if (lines) {
      vertices += 2;
      continue;
    }
    const AssembledPrimitive prim = assemble_primitive(draw, i);
    const bool any = is_clipped(prim.position[0]) || is_clipped(prim.position[1]) || is_clipped(prim.position[2]);
    vertices += any ? kClippedTriangleVertices : 3;
  }
  run.fits_one_batch = vertices <= kVbufBatchVertices;
  return run;
}
// With make_clip_vertex's clip test (clip_test.hpp).
TrailingPipelineRun trailing_pipeline_run(const Draw& draw, const std::vector<bool>& pipelined);

// The mode of primitive `primitive` whose chunk is `pipelined`.
SetupDenormals setup_denormals(const TrailingPipelineRun& run, bool pipelined, uint32_t primitive);

// setup_triangle / setup_line in that mode. EitherMustAgree: NotSupportedError when the two modes
// rasterize differently.
TriangleSetup setup_triangle_in_mode(SetupDenormals mode, const std::array<WindowVertex, 3>& window, uint32_t owner,
                                     const SetupContext& ctx, uint32_t primitive_index);
LineSetup setup_line_in_mode(SetupDenormals mode, const std::array<WindowVertex, 2>& window, uint32_t owner,
                             const SetupContext& ctx, uint32_t primitive_index);

// Whether a depth bias factor is a denormal: a set-up outside the flushed mode then meets one
// whatever its primitive (setup_in_mode's check of its input).
bool depth_bias_is_denormal(const DepthBias& bias);

struct PrimitiveOutcome {
  uint32_t draw_index = 0;
  uint32_t primitive_index = 0;
  bool is_line = false;
  bool pipelined = false;  // some vertex of the primitive's draw chunk needed clipping (§1.5, draw_chunks.hpp)
  SetupDenormals setup_denormals = SetupDenormals::Flushed;
  ClipFate clip_fate = ClipFate::Inside;
  uint32_t piece = 0;         // which triangle of the clipped fan
  uint32_t piece_count = 0;   // triangles (or lines) that reached set-up; 0: none did
  bool float_culled = false;  // dropped by the pipeline float cull (§2.6)
  float float_det = 0;        // its determinant, when it ran
  bool float_cull_ran = false;
  std::array<WindowVertex, 3> window{};  // set-up input (post clip, pre swap)
  SetupFate setup_fate = SetupFate::Rasterized;
  bool reached_setup = false;  // false: clipped away or float-culled
  bool front_facing = false;   // triangles
  int64_t area = 0;            // triangles: doubled fixed-point area
  bool swapped = false;
  PixelRect bbox;  // valid when snapped
  bool has_bbox = false;
  RasterPrimitive raster;  // valid when setup_fate == Rasterized and reached_setup
  bool rasterized() const { return reached_setup && setup_fate == SetupFate::Rasterized; }
};

using OutcomeSink = std::function<void(const PrimitiveOutcome&)>;

// Runs draw `draw_index` of the frame's scene through the geometry stages, in primitive order.
// The set-up context of one draw of the frame (the same for the exact and the fast path).
SetupContext make_setup_context(const FrameContext& frame, uint32_t draw_index);

void run_front_end(const FrameContext& frame, uint32_t draw_index, const OutcomeSink& sink);

// run_front_end one primitive at a time (the fast path's walks, which leave out primitives that
// cannot reach their rows): the draw's state, then primitive i of it through the geometry stages.
struct DrawWalk {
  const Draw* draw = nullptr;
  SetupContext ctx;
  std::vector<bool> pipelined;
  TrailingPipelineRun run;
  uint32_t count = 0, per_chunk = 1;
  PrimitiveOutcome base;
};
DrawWalk begin_draw(const FrameContext& frame, uint32_t draw_index);
// The same with the draw's §1.5 chunk flags and §7.11 trailing run given (formed by
// pipelined_chunks_by and trailing_pipeline_run_of from a clip test made elsewhere).
DrawWalk begin_draw(const FrameContext& frame, uint32_t draw_index, std::vector<bool> pipelined,
                    const TrailingPipelineRun& run);
SetupDenormals primitive_setup_denormals(const DrawWalk& walk, uint32_t primitive);
void run_primitive(const FrameContext& frame, const DrawWalk& walk, uint32_t primitive, const OutcomeSink& sink);

}  // namespace rastercmp::cpu
