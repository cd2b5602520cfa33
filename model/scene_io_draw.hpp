// Draw objects and draw state of a scene file (private to model/scene_io*.cpp).
#pragma once

#include <glm/mat4x4.hpp>

#include "model/scene.hpp"
#include "model/scene_json.hpp"

namespace rastercmp::scene_io_detail {

enum class PositionSpace { Clip, Pixels, World };

// What turns a draw's positions into clip space.
struct PositionContext {
  PositionSpace space = PositionSpace::Clip;
  Viewport viewport;           // Pixels: the effective viewport
  glm::mat4 world_to_clip{1};  // World: projection × view
  bool allow_non_finite = false;
};

// The draw-state keys ("defaults" and each draw): applied over `base`, absent keys keep it.
RasterState read_draw_state(const scene_json::Node& object, RasterState base);

// Checks the "defaults" object (draw state keys only) and applies it to the Vulkan-style defaults.
RasterState read_defaults(const scene_json::Node& defaults);

Draw read_draw(const scene_json::Node& draw, const RasterState& defaults, const PositionContext& context);

}  // namespace rastercmp::scene_io_detail
