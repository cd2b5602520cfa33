// What set-up needs to know besides the primitive: per render (framebuffer, region, methods,
// arithmetic) and per draw (raster and depth state).
#pragma once

#include "cpu_raster/exact/draw_region.hpp"
#include "cpu_raster/exact/setup_methods.hpp"
#include "cpu_raster/exact/work_skips.hpp"
#include "model/lavapipe_release.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

struct SetupContext {
  PixelRect framebuffer;
  PixelRect region;          // framebuffer ∩ scissor ∩ vpwh
  bool multisample = false;  // the framebuffer has 4 samples
  bool fma = true;           // llvm.fmuladd fused
  SetupMethods methods;
  WorkSkips skips;  // depth and bias work done anyway when off (work_skips.hpp)
  LavapipeRules rules;  // the modelled release's (model/lavapipe_release.hpp)
  DepthFormat depth_format = DepthFormat::None;
  const RasterState* state = nullptr;  // the draw's state
  uint32_t draw_index = 0;

  // Depth is produced only with an attachment and the test on (Vulkan: no test, no write).
  bool depth_active() const { return depth_format != DepthFormat::None && state->depth.test_enable; }
  // Whether set-up forms the depth plane: when active, or anyway with the depth skip off.
  bool depth_plane_wanted() const { return depth_active() || !skips.depth_only_when_attached; }
};

}  // namespace rastercmp::cpu
