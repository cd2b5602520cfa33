// Rasterization and per-sample operations of the exact path (docs/lavapipe-rules.md §2.4, §3.3-§3.6, §6):
// for each pixel of the primitive's visit rectangle and each sample, the sample is covered iff all
// plane values are > 0; a covered sample's depth is interpolated, offset, clamped, converted and
// tested; if it passes, depth (when writes are on) and the owner id are written. Later primitives
// overwrite earlier ones. No depth work at all when the draw has no active depth test (unless the
// depth skip is off). Coverage uses 32-bit edge values where the visit rectangle allows it.
#pragma once

#include <cstdint>

#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/edge_frame32.hpp"
#include "cpu_raster/exact/raster_primitive.hpp"
#include "cpu_raster/exact/render_targets.hpp"
#include "cpu_raster/exact/viewport.hpp"
#include "cpu_raster/exact/work_skips.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

struct DepthTestState {
  bool active = false;  // an attachment and depthTestEnable
  bool write = false;
  CompareOp op = CompareOp::Always;
  DepthFormat format = DepthFormat::None;
  DepthRange range;
  bool fma = true;
  // WorkSkips::depth_only_when_attached off: covered samples get their depth computed (and, with an
  // attachment, compared) although the test is not active; the result is discarded.
  bool compute_when_inactive = false;
};

DepthTestState make_depth_test_state(const Scene& scene, const Draw& draw, const ViewportTransform& viewport, bool fma,
                                     const WorkSkips& skips = WorkSkips{});

// Index of the first plane whose value at the point is <= 0, or -1 when the sample is covered.
inline int first_failing_plane(const PlaneSet& planes, int64_t x_fixed, int64_t y_fixed) {
  for (uint32_t i = 0; i < planes.count; ++i)
    if (edge_value(planes.plane[i], x_fixed, y_fixed) <= 0) return int(i);
  return -1;
}

// One sample of one primitive against the stored depth value.
struct SampleVerdict {
  SamplePoint point;
  int failing_plane = -1;    // -1: covered
  SampleDepth depth;         // valid when covered and depth is active
  bool depth_passed = true;  // true when depth is not active
  bool covered() const { return failing_plane < 0; }
  bool passes() const { return covered() && depth_passed; }
};

SampleVerdict evaluate_sample(const RasterPrimitive& primitive, const DepthTestState& depth, int32_t px, int32_t py,
                              uint32_t sample, uint32_t stored_raw);

// The same, with the coverage test in 32 bits when `frame32` is given (edge_frame32.hpp).
SampleVerdict evaluate_sample(const RasterPrimitive& primitive, const DepthTestState& depth, int32_t px, int32_t py,
                              uint32_t sample, uint32_t stored_raw, const EdgeFrame32* frame32);

// `skips`: only edges32_when_box_fits matters here (depth work follows `depth`).
void rasterize_primitive(const RasterPrimitive& primitive, const DepthTestState& depth, RenderTargets& targets,
                         const WorkSkips& skips = WorkSkips{});

}  // namespace rastercmp::cpu
