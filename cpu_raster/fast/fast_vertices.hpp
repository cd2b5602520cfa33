// Per-vertex work of a draw, done once per position instead of once per triangle corner
// (docs/performance.md): the clip test (lavapipe-rules §1.3), the JIT window transform (§1.3)
// and the triangle snap to 24.8 (§2.2). Bit for bit what cpu::make_clip_vertex and
// cpu::snap_vertex give for the same position; an original vertex's window coordinates depend
// on nothing but its position, so sharing them between triangles changes nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cpu_raster/viewport.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::fast {

inline constexpr uint32_t kVertexClipBits = 0x3Fu;         // cpu::ClipPlane bits 0..5
inline constexpr uint32_t kVertexSnapFailed = 1u << 6;     // snap_vertex gave nullopt (NaN, Inf, out of range)

// Trivial on purpose: a draw's array is allocated without initialisation and filled by a pass.
// 32 bytes, so that one 256-bit load fetches a vertex (small_triangles_avx2.cpp).
struct FastVertex {
  int32_t x_fixed, y_fixed;  // snapped with the single-sample pixel offset 0.5
  float x, y, z;             // window coordinates (JIT path)
  uint32_t flags;            // clip mask | kVertexSnapFailed
  uint32_t unused[2];
};
static_assert(sizeof(FastVertex) == 32);

struct VertexJob {
  const glm::vec4* pos_clip = nullptr;
  ViewportTransform viewport;
  bool fma = true;
  bool depth_clip = true;
};

// Per vertex, the 64-pixel tile row of its snapped y (y_fixed >> 14), or kRowUnknown when the
// vertex needs clipping or failed to snap: a compact copy for the block row test (band_worker.cpp).
inline constexpr int16_t kRowUnknown = INT16_MIN;

// Fills out[begin, end) and rows[begin, end) from job.pos_clip[begin, end); returns the OR of
// the vertices' flags.
uint32_t transform_vertices_scalar(const VertexJob& job, size_t begin, size_t end, FastVertex* out, int16_t* rows);
uint32_t transform_vertices_avx2(const VertexJob& job, size_t begin, size_t end, FastVertex* out, int16_t* rows);

}  // namespace rastercmp::cpu::fast
