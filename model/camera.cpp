#include "model/camera.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace rastercmp {

glm::mat4 camera_world_to_clip(const Camera& camera, float aspect) {
  const glm::mat4 view = glm::lookAt(camera.eye, camera.target, camera.up);
  // GLM_FORCE_DEPTH_ZERO_TO_ONE (model/CMakeLists.txt): clip z in 0..w, as Vulkan expects.
  // glm::perspective (right-handed, depth 0..1), but for tan: the float tanf of glibc 2.36 and of
  // 2.41 (correctly rounded) differ in the last bit for some angles, and a scene must give the same
  // clip positions on every system, or a render captured on one is not the scene judged on another.
  // tan in double, rounded once to float, is the correctly rounded value wherever libm's double tan
  // is within an ulp.
  const float tan_half_fov = static_cast<float>(std::tan(double(glm::radians(camera.fov_y_degrees)) / 2.0));
  const float near_plane = camera.near_plane, far_plane = camera.far_plane;
  glm::mat4 projection(0.0f);
  projection[0][0] = 1.0f / (aspect * tan_half_fov);
  projection[1][1] = -(1.0f / tan_half_fov);  // GL's y-up projection → Vulkan's y-down framebuffer
  projection[2][2] = far_plane / (near_plane - far_plane);
  projection[2][3] = -1.0f;
  projection[3][2] = -(far_plane * near_plane) / (far_plane - near_plane);
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
