// The attachments the exact path writes: per-sample owner ids and raw depth bits, cleared as the
// Vulkan side clears them (owner: kOwnerBackground; depth: the scene's clear value, packed).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

struct RenderTargets {
  uint32_t width = 0, height = 0, samples = 1;
  DepthFormat depth_format = DepthFormat::None;
  PixelBuffer owner;      // (y * width + x) * samples + sample
  PixelBuffer depth_raw;  // same layout; empty without a depth attachment

  size_t index(int32_t x, int32_t y, uint32_t sample) const {
    return (size_t(y) * width + size_t(x)) * samples + sample;
  }
};

RenderTargets make_render_targets(const Scene& scene);

// Moves the attachments into `result` as a CPU render: backend "cpu", `device`, `fma`, the sizes,
// owner ids and raw depth (any coverage classes left from an earlier render are cleared).
void move_into_result(RenderTargets&& targets, const std::string& device, bool fma, RenderResult& result);

}  // namespace rastercmp::cpu
