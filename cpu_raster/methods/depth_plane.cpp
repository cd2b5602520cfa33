#include "cpu_raster/methods/depth_plane.hpp"

#include <cmath>

namespace rastercmp::methods {

// docs/lavapipe-rules.md §3.2: every line one float32 operation (-ffp-contract=off keeps it so).
DepthPlane setup_depth_plane(const std::array<Vec3f, 3>& pos_window, float pixel_center) {
  const Vec3f v0 = pos_window[0], v1 = pos_window[1], v2 = pos_window[2];
  const float x0_center = v0.x - pixel_center, y0_center = v0.y - pixel_center;
  const float dx01 = v0.x - v1.x, dy01 = v0.y - v1.y, dx20 = v2.x - v0.x, dy20 = v2.y - v0.y;
  const float e = dx01 * dy20, f = dy01 * dx20;
  const float ooa = 1.0f / (e - f);
  const float dx20_ooa = dx20 * ooa, dy20_ooa = dy20 * ooa, dx01_ooa = dx01 * ooa, dy01_ooa = dy01 * ooa;
  const float dz01 = v0.z - v1.z, dz20 = v2.z - v0.z;
  DepthPlane plane;
  plane.dzdx = (dz01 * dy20_ooa) - (dz20 * dy01_ooa);
  plane.dzdy = (dz20 * dx01_ooa) - (dz01 * dx20_ooa);
  plane.a0 = v0.z - ((plane.dzdx * x0_center) + (plane.dzdy * y0_center));
  return plane;
}

float eval_depth_unfused(const DepthPlane& plane, int32_t px, int32_t py) {
  const float along_x = plane.dzdx * float(px);
  const float at_x = plane.a0 + along_x;
  const float along_y = plane.dzdy * float(py);
  return at_x + along_y;
}

float eval_depth_fused(const DepthPlane& plane, int32_t px, int32_t py) {
  return std::fma(plane.dzdy, float(py), std::fma(plane.dzdx, float(px), plane.a0));
}

}  // namespace rastercmp::methods
