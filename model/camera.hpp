// Positions given in "pixels" or "world" space → Vulkan clip space, once, on the host, so both
// renderers start from the same bits (docs/lavapipe-rules.md §1.7; docs/scene-format.md).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "model/scene.hpp"

namespace rastercmp {

// projection × view of a right-handed look-at camera: glm::lookAt, then glm::perspective with
// Vulkan's 0..1 clip depth and the y axis flipped, so world "up" is up in the image (Vulkan's
// framebuffer y grows downwards). `aspect` = viewport width / |viewport height|.
glm::mat4 camera_world_to_clip(const Camera& camera, float aspect);

// A camera whose up vector is parallel to the view direction (or zero) has no view matrix.
bool camera_up_is_degenerate(const Camera& camera);

// [x, y, z, w] with x, y in framebuffer pixels and z a depth value → clip space, inverting the
// viewport transform (Vulkan spec "Controlling the Viewport"):
//   x_c = w * (x - o_x) / (p_x / 2),  y_c likewise,  z_c = w * (z - o_z) / p_z,
// with o_x = x_vp + width/2, p_x = width, o_z = min_depth, p_z = max_depth - min_depth.
// Computed in double precision and rounded to float once. Needs p_z != 0.
glm::vec4 pixels_to_clip(const Viewport& viewport, const glm::vec4& pos_pixels);

}  // namespace rastercmp
