#include "model/camera.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace rastercmp {

glm::mat4 camera_world_to_clip(const Camera& camera, float aspect) {
  const glm::mat4 view = glm::lookAt(camera.eye, camera.target, camera.up);
  // GLM_FORCE_DEPTH_ZERO_TO_ONE (model/CMakeLists.txt): clip z in 0..w, as Vulkan expects.
  glm::mat4 projection =
      glm::perspective(glm::radians(camera.fov_y_degrees), aspect, camera.near_plane, camera.far_plane);
  projection[1][1] = -projection[1][1];  // GL's y-up projection → Vulkan's y-down framebuffer
  return projection * view;
}

bool camera_up_is_degenerate(const Camera& camera) {
  const glm::dvec3 forward = glm::dvec3(camera.target) - glm::dvec3(camera.eye);
  const glm::dvec3 up = glm::dvec3(camera.up);
  const double side = glm::length(glm::cross(forward, up));
  return !(side > 1e-9 * glm::length(forward) * glm::length(up));
}

glm::vec4 pixels_to_clip(const Viewport& viewport, const glm::vec4& pos_pixels) {
  const double w = pos_pixels.w;
  const double half_width = double(viewport.width) / 2;
  const double half_height = double(viewport.height) / 2;
  const double o_x = double(viewport.x) + half_width;
  const double o_y = double(viewport.y) + half_height;
  const double o_z = viewport.min_depth;
  const double p_z = double(viewport.max_depth) - double(viewport.min_depth);
  return glm::vec4(float(w * ((pos_pixels.x - o_x) / half_width)), float(w * ((pos_pixels.y - o_y) / half_height)),
                   float(w * ((pos_pixels.z - o_z) / p_z)), pos_pixels.w);
}

}  // namespace rastercmp
