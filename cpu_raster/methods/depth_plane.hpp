// Depth as a plane in window space, set up once per triangle and evaluated per pixel WITHOUT
// fused multiply-add: the textbook evaluation z = a0 + dz/dx * px + dz/dy * py with every product
// and sum rounded to float32 on its own.
//
// The set-up follows lavapipe's float32 operation order (docs/lavapipe-rules.md §3.2), so the
// only difference from lavapipe's per-pixel evaluation, z = fma(dzdy, py, fma(dzdx, px, a0))
// (§3.3, FMA hosts), is the fusing. eval_depth_fused is that form, for comparison.
//
// Does: the plane of three window-space vertices (x, y in pixels, z in 0..1), its evaluation at
//       pixel (px, py) (the pixel_center offset is folded into a0, §3.2), fused or not.
// Does not: clamp, convert to a depth format, add depth bias, or handle zero-area triangles
//       (1/area is inf and the plane is meaningless; callers drop such triangles first).
#pragma once

#include <array>
#include <cstdint>

namespace rastercmp::methods {

struct Vec3f {
  float x = 0, y = 0, z = 0;
};

struct DepthPlane {
  float dzdx = 0, dzdy = 0;
  float a0 = 0;  // plane value at pixel (0, 0), i.e. at window point (pixel_center, pixel_center)
};

// pixel_center: 0.5 for single-sample (sample at the pixel centre), 0 for per-sample evaluation.
DepthPlane setup_depth_plane(const std::array<Vec3f, 3>& pos_window, float pixel_center = 0.5f);

// fl(fl(a0 + fl(dzdx * px)) + fl(dzdy * py)): no fused multiply-add.
float eval_depth_unfused(const DepthPlane& plane, int32_t px, int32_t py);

// fma(dzdy, py, fma(dzdx, px, a0)): lavapipe's JIT evaluation on FMA hosts (§3.3).
float eval_depth_fused(const DepthPlane& plane, int32_t px, int32_t py);

}  // namespace rastercmp::methods
