// Per-vertex work of a draw, done once per position instead of once per triangle corner
// (docs/performance.md): the clip test (docs/lavapipe-rules.md §1.3), the JIT window transform (§1.3)
// and the triangle snap to 24.8 (§2.2). Bit for bit what cpu::make_clip_vertex and
// cpu::snap_vertex give for the same position; an original vertex's window coordinates depend
// on nothing but its position, so sharing them between triangles changes nothing.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include "cpu_raster/exact/viewport.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::fast {

inline constexpr uint32_t kVertexClipBits = 0x3Fu;      // cpu::ClipPlane bits 0..5
inline constexpr uint32_t kVertexSnapFailed = 1u << 6;  // snap_vertex gave nullopt (NaN, Inf, out of range)

// A triangle with these corner flags goes through the clipper: some corner is outside a clip
// plane, and not all three outside the same one (that is ClipFate::Outside: nothing to draw).
inline bool needs_clipping(uint32_t f0, uint32_t f1, uint32_t f2) {
  return ((f0 | f1 | f2) & kVertexClipBits) != 0 && (f0 & f1 & f2 & kVertexClipBits) == 0;
}

// Trivial on purpose: a draw's array is allocated without initialisation and filled by a pass.
// 16 bytes: the snapped coordinates are not stored but recomputed where they are used
// (snap_fixed, a subtraction, an exact multiply and a conversion): the array is written once and
// read by every triangle, and on a mesh of a million triangles its size is what the phases wait on.
struct FastVertex {
  float x, y, z;   // window coordinates (JIT path)
  uint32_t flags;  // clip mask | kVertexSnapFailed
};
static_assert(sizeof(FastVertex) == 16);

// snap_vertex(window, 0.5, NearestEven)->raw (§2.2: fl(window - 0.5) * 256, exact, rounded to
// nearest even) for a vertex whose flags lack kVertexSnapFailed (then |raw| <= 2^25 and the
// conversion is exact); cvtss2si rounds to nearest even in the default rounding mode.
inline int32_t snap_fixed(float window) {
#if defined(__x86_64__) || defined(__i386__)
  return _mm_cvtss_si32(_mm_set_ss((window - 0.5f) * 256.0f));
#else
  return int32_t(std::nearbyint((window - 0.5f) * 256.0f));
#endif
}

struct VertexJob {
  const glm::vec4* pos_clip = nullptr;
  ViewportTransform viewport;
  bool fma = true;
  bool depth_clip = true;
};

// Per vertex, the 64-pixel tile row of its snapped y (y_fixed >> 14, in [-2048, 2048] since
// |y_fixed| <= 2^25), or, when the vertex needs clipping or failed to snap, unknown_row(flags):
// kRowUnknown with the vertex's flags (7 bits) in its low bits, below every known row. A compact
// copy for the block-row phase (block_rows.hpp), which reads both the rows and the shared clip
// bits from it (2 bytes a position instead of the FastVertex's 16).
inline constexpr int16_t kRowUnknown = INT16_MIN;
inline constexpr int16_t unknown_row(uint32_t flags) { return int16_t(kRowUnknown | int32_t(flags & 0x7Fu)); }
inline constexpr int32_t kLastUnknownRow = kRowUnknown + 0x7F;  // unknown_row of every flag
inline constexpr bool is_unknown_row(int32_t row) { return row <= kLastUnknownRow; }
// The clip bits an entry of tile_rows holds (none for a known row).
inline constexpr uint32_t row_clip_bits(int32_t row) {
  return is_unknown_row(row) ? uint32_t(row) & kVertexClipBits : 0;
}
static_assert(kVertexSnapFailed <= 0x7Fu && -2048 > kLastUnknownRow, "flags fit below every known row");

// Fills out[begin, end) and rows[begin, end) from job.pos_clip[begin, end); returns the OR of
// the vertices' flags.
uint32_t transform_vertices_scalar(const VertexJob& job, size_t begin, size_t end, FastVertex* out, int16_t* rows);
uint32_t transform_vertices_avx2(const VertexJob& job, size_t begin, size_t end, FastVertex* out, int16_t* rows);
// The same sixteen at a time (fast_vertices_avx512.cpp); call only when host_has_avx512().
uint32_t transform_vertices_avx512(const VertexJob& job, size_t begin, size_t end, FastVertex* out, int16_t* rows);

}  // namespace rastercmp::cpu::fast
