#include "cpu_raster/exact/clip_vertex.hpp"

#include "cpu_raster/exact/clip_test.hpp"

namespace rastercmp::cpu {

ClipVertex make_clip_vertex(const glm::vec4& pos_clip, const ViewportTransform& viewport, bool depth_clip, bool fma) {
  return ClipVertex{pos_clip, window_from_clip_jit(pos_clip, viewport, fma), clip_mask(pos_clip, depth_clip), false};
}

ClipVertex interpolate_clip_vertex(float t, const ClipVertex& out, const ClipVertex& in,
                                   const ViewportTransform& viewport) {
  glm::vec4 pos;
  for (int k = 0; k < 4; ++k) pos[k] = out.pos_clip[k] + t * (in.pos_clip[k] - out.pos_clip[k]);  // LINTERP
  return ClipVertex{pos, window_from_clip_c(pos, viewport), 0, true};
}

}  // namespace rastercmp::cpu
