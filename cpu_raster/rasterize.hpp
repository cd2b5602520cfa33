// Rasterization and per-sample operations of the exact path (lavapipe-rules §2.4, §3.3-§3.6, §6):
// for each pixel of the primitive's visit rectangle and each sample, the sample is covered iff all
// plane values are > 0; a covered sample's depth is interpolated, offset, clamped, converted and
// tested; if it passes, depth (when writes are on) and the owner id are written. Later primitives
// overwrite earlier ones. No depth work at all when the draw has no active depth test.
#pragma once

#include <cstdint>

#include "cpu_raster/depth_sample.hpp"
#include "cpu_raster/raster_primitive.hpp"
#include "cpu_raster/render_targets.hpp"
#include "cpu_raster/viewport.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

struct DepthTestState {
  bool active = false;  // an attachment and depthTestEnable
  bool write = false;
  CompareOp op = CompareOp::Always;
  DepthFormat format = DepthFormat::None;
  DepthRange range;
  bool fma = true;
};

DepthTestState make_depth_test_state(const Scene& scene, const Draw& draw, const ViewportTransform& viewport, bool fma);

// Index of the first plane whose value at the point is <= 0, or -1 when the sample is covered.
inline int first_failing_plane(const PlaneSet& planes, int64_t x_fixed, int64_t y_fixed) {
  for (uint32_t i = 0; i < planes.count; ++i)
    if (edge_value(planes.plane[i], x_fixed, y_fixed) <= 0) return int(i);
  return -1;
}

// One sample of one primitive against the stored depth value.
struct SampleVerdict {
  SamplePoint point;
  int failing_plane = -1;   // -1: covered
  SampleDepth depth;        // valid when covered and depth is active
  bool depth_passed = true; // true when depth is not active
  bool covered() const { return failing_plane < 0; }
  bool passes() const { return covered() && depth_passed; }
};

SampleVerdict evaluate_sample(const RasterPrimitive& primitive, const DepthTestState& depth, int32_t px, int32_t py,
                              uint32_t sample, uint32_t stored_raw);

void rasterize_primitive(const RasterPrimitive& primitive, const DepthTestState& depth, RenderTargets& targets);

}  // namespace rastercmp::cpu
