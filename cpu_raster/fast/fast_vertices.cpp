#include "cpu_raster/fast/fast_vertices.hpp"

#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/fixed_point.hpp"

namespace rastercmp::cpu::fast {

uint32_t transform_vertices_scalar(const VertexJob& job, size_t begin, size_t end, FastVertex* out, int16_t* rows) {
  uint32_t all_flags = 0;
  for (size_t k = begin; k < end; ++k) {
    const glm::vec4& p = job.pos_clip[k];
    const WindowVertex w = window_from_clip_jit(p, job.viewport, job.fma);  // §1.3
    FastVertex& v = out[k];
    v.x = w.x;
    v.y = w.y;
    v.z = w.z;
    v.flags = clip_mask(p, job.depth_clip);
    const auto x = snap_vertex(w.x, 0.5f, SnapRounding::NearestEven);  // §2.2, single sample
    const auto y = snap_vertex(w.y, 0.5f, SnapRounding::NearestEven);
    if (!x || !y) v.flags |= kVertexSnapFailed;
    // |y->raw| <= 2^25 (Fixed24_8::kMaxMagnitude), so the row fits 16 bits
    rows[k] = v.flags ? unknown_row(v.flags) : int16_t(y->raw >> (kFixedOrder + 6));
    all_flags |= v.flags;
  }
  return all_flags;
}

}  // namespace rastercmp::cpu::fast
