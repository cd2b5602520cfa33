#include "cpu_raster/exact/clip_test.hpp"

#include "cpu_raster/exact/float_ops.hpp"

namespace rastercmp::cpu {
namespace {

// draw_context.c draw_init, plane 4 replaced for clip_halfz in draw_pt_post_vs.c (§1.5).
constexpr float kPlanes[kClipPlaneCount][4] = {
    {-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 0}, {0, 0, -1, 1},
};

}  // namespace

uint32_t clip_mask(const glm::vec4& p, bool depth_clip) {
  uint32_t mask = 0;  // draw_llvm.c generate_clipmask (§1.3)
  if (unordered_greater(p.x, p.w)) mask |= 1u << kClipRight;
  if (unordered_greater(0.0f, p.x + p.w)) mask |= 1u << kClipLeft;
  if (unordered_greater(p.y, p.w)) mask |= 1u << kClipBottom;
  if (unordered_greater(0.0f, p.y + p.w)) mask |= 1u << kClipTop;
  if (depth_clip) {
    if (unordered_greater(0.0f, p.z)) mask |= 1u << kClipNear;
    if (unordered_greater(p.z, p.w)) mask |= 1u << kClipFar;
  }
  return mask;
}

float plane_distance(const glm::vec4& p, uint32_t plane) {
  const float* a = kPlanes[plane];
  return p.x * a[0] + p.y * a[1] + p.z * a[2] + p.w * a[3];  // left to right, each rounded
}

}  // namespace rastercmp::cpu
