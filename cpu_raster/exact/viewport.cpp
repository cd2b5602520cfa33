#include "cpu_raster/exact/viewport.hpp"

#include "cpu_raster/exact/float_ops.hpp"

namespace rastercmp::cpu {

ViewportTransform make_viewport_transform(const Viewport& viewport) {
  const DenormalsKept state_time;  // lvp computes these outside draw_vbo: no FTZ/DAZ (rules §7.10)
  ViewportTransform t;
  const float half_width = 0.5f * viewport.width;  // docs/lavapipe-rules.md §1.2
  const float half_height = 0.5f * viewport.height;
  t.scale[0] = half_width;
  t.translate[0] = half_width + viewport.x;
  t.scale[1] = half_height;
  t.translate[1] = half_height + viewport.y;
  // n and f are double copies of minDepth/maxDepth; the difference is stored as float (step 2).
  t.scale[2] = static_cast<float>(double(viewport.max_depth) - double(viewport.min_depth));
  t.translate[2] = viewport.min_depth;
  const float far_end = t.translate[2] + t.scale[2];  // need not equal maxDepth bit for bit (§3.4)
  t.zmin = t.translate[2] < far_end ? t.translate[2] : far_end;
  t.zmax = t.translate[2] < far_end ? far_end : t.translate[2];
  return t;
}

WindowVertex window_from_clip_jit(const glm::vec4& pos_clip, const ViewportTransform& v, bool fma) {
  const float oow = 1.0f / pos_clip.w;  // draw_llvm.c generate_viewport: 1/w, then a multiply
  return WindowVertex{mul_add(pos_clip.x * oow, v.scale[0], v.translate[0], fma),
                      mul_add(pos_clip.y * oow, v.scale[1], v.translate[1], fma),
                      mul_add(pos_clip.z * oow, v.scale[2], v.translate[2], fma)};
}

WindowVertex window_from_clip_c(const glm::vec4& pos_clip, const ViewportTransform& v) {
  const float oow = 1.0f / pos_clip.w;  // draw_pipe_clip.c interp()
  return WindowVertex{pos_clip.x * oow * v.scale[0] + v.translate[0], pos_clip.y * oow * v.scale[1] + v.translate[1],
                      pos_clip.z * oow * v.scale[2] + v.translate[2]};
}

}  // namespace rastercmp::cpu
