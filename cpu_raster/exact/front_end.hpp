// The geometry half of the exact path, per draw: assemble → clip test → clip → viewport →
// pipeline float cull → set-up. Each primitive reports one outcome per piece that reached set-up
// (a clipped triangle can become several), or one outcome saying why nothing did. The renderer
// rasterizes the outcomes; explain inspects them. Both call this same function.
#pragma once

#include <cstdint>
#include <functional>

#include "cpu_raster/exact/clip_triangle.hpp"
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

struct PrimitiveOutcome {
  uint32_t draw_index = 0;
  uint32_t primitive_index = 0;
  bool is_line = false;
  bool pipelined = false;  // some vertex of the primitive's draw chunk needed clipping (§1.5, draw_chunks.hpp)
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

}  // namespace rastercmp::cpu
