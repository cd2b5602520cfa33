// setup_small_block_avx2 and setup_small_block_avx512 (small_triangles.hpp): this body is
// compiled twice, by small_triangles_avx2.cpp and small_triangles_avx512.cpp, which define
// RASTERCMP_SMALL_TARGET (the target attribute) and RASTERCMP_SMALL_SETUP (the function's name).
// The AVX-512 build runs the same 256-bit intrinsics with 32 vector registers (fewer spills). Both
// may hand blocks to the window compositor (small_window.hpp). Every float operation is the
// scalar set-up's (depth_plane.cpp triangle_depth_plane, §3.2), one IEEE operation per intrinsic
// and no fusion.
#include <immintrin.h>

#include <algorithm>
#include <climits>

#include "cpu_raster/fast/avx2_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"
#include "cpu_raster/fast/small_triangles.hpp"

namespace rastercmp::cpu::fast {
namespace {

struct Corners {  // one triangle corner of eight lanes
  __m256i x_fixed, y_fixed, flags;
  __m256 x, y, z;
};

// snap_fixed of eight lanes: fl(c - 0.5) * 256 (exact), converted rounding to nearest even.
// Lanes whose vertex failed to snap get INT32_MIN; they are special lanes, never drawn here.
RASTERCMP_SMALL_TARGET inline __m256i snap_fixed8(__m256 c) {
  return _mm256_cvtps_epi32(_mm256_mul_ps(_mm256_sub_ps(c, _mm256_set1_ps(0.5f)), _mm256_set1_ps(256.0f)));
}

// Eight FastVertex (16 bytes each) → one register per field (a 4x8 transpose), without the snap.
RASTERCMP_SMALL_TARGET inline Corners load_fields(const FastVertex* v, const uint32_t* index, uint32_t stride) {
  __m256 r[4];  // vertices k and k + 4
  for (uint32_t k = 0; k < 4; ++k)
    r[k] = _mm256_insertf128_ps(
        _mm256_castps128_ps256(_mm_loadu_ps(reinterpret_cast<const float*>(v + index[k * stride]))),
        _mm_loadu_ps(reinterpret_cast<const float*>(v + index[(k + 4) * stride])), 1);
  const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);  // x0 x1 y0 y1, z0 z1 f0 f1
  const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
  Corners c;
  c.x = _mm256_shuffle_ps(t0, t2, 0x44);
  c.y = _mm256_shuffle_ps(t0, t2, 0xEE);
  c.z = _mm256_shuffle_ps(t1, t3, 0x44);
  c.flags = _mm256_castps_si256(_mm256_shuffle_ps(t1, t3, 0xEE));
  return c;
}

// The fields and the snap.
RASTERCMP_SMALL_TARGET inline Corners load_corners(const FastVertex* v, const uint32_t* index, uint32_t stride) {
  Corners c = load_fields(v, index, stride);
  c.x_fixed = snap_fixed8(c.x);
  c.y_fixed = snap_fixed8(c.y);
  return c;
}

RASTERCMP_SMALL_TARGET inline __m256i min3(__m256i a, __m256i b, __m256i c) {
  return _mm256_min_epi32(a, _mm256_min_epi32(b, c));
}
RASTERCMP_SMALL_TARGET inline __m256i max3(__m256i a, __m256i b, __m256i c) {
  return _mm256_max_epi32(a, _mm256_max_epi32(b, c));
}
RASTERCMP_SMALL_TARGET inline __m256i not_mask(__m256i m) { return _mm256_xor_si256(m, _mm256_set1_epi32(-1)); }
RASTERCMP_SMALL_TARGET inline uint32_t lanes(__m256i m) { return uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(m))); }

RASTERCMP_SMALL_TARGET inline void swap_where(__m256i mask, __m256i& a, __m256i& b) {
  const __m256i na = _mm256_blendv_epi8(a, b, mask), nb = _mm256_blendv_epi8(b, a, mask);
  a = na;
  b = nb;
}
RASTERCMP_SMALL_TARGET inline void swap_where(__m256i mask, __m256& a, __m256& b) {
  const __m256 m = _mm256_castsi256_ps(mask);
  const __m256 na = _mm256_blendv_ps(a, b, m), nb = _mm256_blendv_ps(b, a, m);
  a = na;
  b = nb;
}

// The faces the cull mode drops, given which lanes are front-facing.
RASTERCMP_SMALL_TARGET inline __m256i culled(CullMode cull, __m256i front) {
  switch (cull) {
    case CullMode::None: return _mm256_setzero_si256();
    case CullMode::Front: return front;
    case CullMode::Back: return not_mask(front);
    case CullMode::FrontAndBack: return _mm256_set1_epi32(-1);
  }
  return _mm256_setzero_si256();
}

struct Plane8 {
  __m256 a0, dzdx, dzdy;
};

// triangle_depth_plane(window, 0.5f) on the post-swap corners p0, p1, p2.
RASTERCMP_SMALL_TARGET inline Plane8 depth_plane8(const Corners& p0, const Corners& p1, const Corners& p2) {
  const __m256 half = _mm256_set1_ps(0.5f);
  const __m256 x0_center = _mm256_sub_ps(p0.x, half), y0_center = _mm256_sub_ps(p0.y, half);
  const __m256 dx01 = _mm256_sub_ps(p0.x, p1.x), dy01 = _mm256_sub_ps(p0.y, p1.y);
  const __m256 dx20 = _mm256_sub_ps(p2.x, p0.x), dy20 = _mm256_sub_ps(p2.y, p0.y);
  const __m256 e = _mm256_mul_ps(dx01, dy20), f = _mm256_mul_ps(dy01, dx20);
  const __m256 ooa = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sub_ps(e, f));
  const __m256 dx20_ooa = _mm256_mul_ps(dx20, ooa), dy20_ooa = _mm256_mul_ps(dy20, ooa);
  const __m256 dx01_ooa = _mm256_mul_ps(dx01, ooa), dy01_ooa = _mm256_mul_ps(dy01, ooa);
  const __m256 dz01 = _mm256_sub_ps(p0.z, p1.z), dz20 = _mm256_sub_ps(p2.z, p0.z);
  Plane8 plane;
  plane.dzdx = _mm256_sub_ps(_mm256_mul_ps(dz01, dy20_ooa), _mm256_mul_ps(dz20, dy01_ooa));
  plane.dzdy = _mm256_sub_ps(_mm256_mul_ps(dz20, dx01_ooa), _mm256_mul_ps(dz01, dx20_ooa));
  plane.a0 =
      _mm256_sub_ps(p0.z, _mm256_add_ps(_mm256_mul_ps(plane.dzdx, x0_center), _mm256_mul_ps(plane.dzdy, y0_center)));
  return plane;
}

// Edge from corner i to corner j (make_edge): dcdx = y_i - y_j, dcdy = x_i - x_j, and the
// top-left rule's +1 folded with the sign test's -1 (is_top_left, §2.4).
struct Edge8 {
  __m256i xi, yi, dcdx, dcdy, bias_minus_1;  // bias_minus_1: 0 on inclusive edges, -1 otherwise
};

RASTERCMP_SMALL_TARGET inline Edge8 edge8(__m256i xi, __m256i yi, __m256i xj, __m256i yj) {
  const __m256i zero = _mm256_setzero_si256();
  Edge8 e{xi, yi, _mm256_sub_epi32(yi, yj), _mm256_sub_epi32(xi, xj), zero};
  const __m256i inclusive =
      _mm256_or_si256(_mm256_cmpgt_epi32(zero, e.dcdx),
                      _mm256_and_si256(_mm256_cmpeq_epi32(e.dcdx, zero), _mm256_cmpgt_epi32(e.dcdy, zero)));
  e.bias_minus_1 = not_mask(inclusive);
  return e;
}

// E - 1 at pixel (ox, oy): dcdx*(x_i - 256*ox) - dcdy*(y_i - 256*oy) + inclusive - 1.
RASTERCMP_SMALL_TARGET inline __m256i edge_at(const Edge8& e, __m256i ox, __m256i oy) {
  const __m256i v = _mm256_sub_epi32(_mm256_mullo_epi32(e.dcdx, _mm256_sub_epi32(e.xi, _mm256_slli_epi32(ox, 8))),
                                     _mm256_mullo_epi32(e.dcdy, _mm256_sub_epi32(e.yi, _mm256_slli_epi32(oy, 8))));
  return _mm256_add_epi32(v, e.bias_minus_1);
}
RASTERCMP_SMALL_TARGET inline __m256i step_x(const Edge8& e) {
  return _mm256_slli_epi32(_mm256_sub_epi32(_mm256_setzero_si256(), e.dcdx), 8);
}
RASTERCMP_SMALL_TARGET inline __m256i step_y(const Edge8& e) { return _mm256_slli_epi32(e.dcdy, 8); }

// The per-triangle kernel jobs' edges, relative to (origin_x, y0).
RASTERCMP_SMALL_TARGET void store_job_edges(const Edge8 (&edges)[3], __m256i ox, __m256i oy, SmallBlockOutput& out) {
  for (int i = 0; i < 3; ++i) {
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.g_minus_1[i]), edge_at(edges[i], ox, oy));
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.gx[i]), step_x(edges[i]));
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.gy[i]), step_y(edges[i]));
  }
}

struct GridLanes {
  __m256i mask, x0, y0, w, h;  // w, h: rectangle width and height minus 1
  int columns, rows;           // the largest over the grid lanes
  int shift;                   // log2 of the side of the bit layout (SmallBlockOutput::grid_shift)
};

// Coverage and raw depth of every candidate pixel of the grid lanes, one pixel position per step.
// Bit p = dy << Shift + dx (SmallBlockOutput::grid_shift), over the block's columns x rows. A row's coverage is
// gathered as bits dx (a blend on the sign of e0|e1|e2, i.e. all three E - 1 >= 0), then cut to
// the lanes that reach the row and shifted into place.
template <DepthFormat F, int Shift>
RASTERCMP_SMALL_TARGET void evaluate_grid(const GridLanes& g, const Edge8 (&edges)[3], const Plane8& plane,
                                          const KernelDepth& depth_state, SmallBlockOutput& out) {
  // A local copy: the stores into `out` might alias the caller's KernelDepth as far as the
  // compiler knows, which made the loop reload fma and clamp at every pixel position.
  const KernelDepth depth = depth_state;
  const int columns = g.columns, rows = g.rows;
  __m256i row_e[3], gx[3], gy[3];
  for (int i = 0; i < 3; ++i) {
    row_e[i] = edge_at(edges[i], g.x0, g.y0);
    gx[i] = step_x(edges[i]);
    gy[i] = step_y(edges[i]);
  }
  // Per column: bit dx in the lanes whose rectangle reaches it; the inner FMA?(dzdx, px, a0),
  // which depends on the column only.
  __m256i column_bit[kGridSide];
  __m256 inner[kGridSide];
  for (int dx = 0; dx < columns; ++dx) {
    column_bit[dx] = _mm256_andnot_si256(_mm256_cmpgt_epi32(_mm256_set1_epi32(dx), g.w), _mm256_set1_epi32(1 << dx));
    if constexpr (F != DepthFormat::None) {
      const __m256 px = _mm256_cvtepi32_ps(_mm256_add_epi32(g.x0, _mm256_set1_epi32(dx)));
      inner[dx] = mul_add8(plane.dzdx, px, plane.a0, depth.fma);
    }
  }
  // Coverage bits per lane: positions 0-31 in bits_lo, 32-63 in bits_hi (32-bit lanes).
  __m256i bits_lo = _mm256_setzero_si256(), bits_hi = _mm256_setzero_si256();
  for (int dy = 0; dy < rows; ++dy) {
    const __m256i in_y = _mm256_andnot_si256(_mm256_cmpgt_epi32(_mm256_set1_epi32(dy), g.h), g.mask);
    const __m256 py = _mm256_cvtepi32_ps(_mm256_add_epi32(g.y0, _mm256_set1_epi32(dy)));
    __m256i e[3] = {row_e[0], row_e[1], row_e[2]};
    __m256 row_bits = _mm256_setzero_ps();
    for (int dx = 0; dx < columns; ++dx) {
      const __m256 outside =
          _mm256_castsi256_ps(_mm256_or_si256(_mm256_or_si256(e[0], e[1]), e[2]));  // sign: some E <= 0
      row_bits = _mm256_blendv_ps(_mm256_or_ps(row_bits, _mm256_castsi256_ps(column_bit[dx])), row_bits, outside);
      if constexpr (F != DepthFormat::None) {
        // + o with o = 0 (draws with depth bias take the scalar set-up); the add turns -0 into +0
        const __m256 z = finish_depth8(mul_add8(plane.dzdy, py, inner[dx], depth.fma), _mm256_setzero_ps(), depth);
        _mm256_store_si256(reinterpret_cast<__m256i*>(out.grid_raw[(dy << Shift) + dx]), to_raw<F>(z));
      }
      for (int i = 0; i < 3; ++i) e[i] = _mm256_add_epi32(e[i], gx[i]);
    }
    const int p0 = dy << Shift;  // the row's first position
    const __m256i placed =
        _mm256_sll_epi32(_mm256_and_si256(_mm256_castps_si256(row_bits), in_y), _mm_cvtsi32_si128(p0 & 31));
    if (p0 < 32)
      bits_lo = _mm256_or_si256(bits_lo, placed);
    else
      bits_hi = _mm256_or_si256(bits_hi, placed);
    for (int i = 0; i < 3; ++i) row_e[i] = _mm256_add_epi32(row_e[i], gy[i]);
  }
  // Interleave into 64-bit lanes: grid_bits[l] = lo[l] | hi[l] << 32.
  const __m256i lo4 = _mm256_unpacklo_epi32(bits_lo, bits_hi), hi4 = _mm256_unpackhi_epi32(bits_lo, bits_hi);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.grid_bits), _mm256_permute2x128_si256(lo4, hi4, 0x20));
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.grid_bits + 4), _mm256_permute2x128_si256(lo4, hi4, 0x31));
  if constexpr (Shift == kSmallGridShift) {  // 16 bits per lane: lanes 0-3 and 4-7 packed into one word each
    const __m256i packed = _mm256_packus_epi32(bits_lo, _mm256_setzero_si256());  // bits < 2^16: no saturation
    out.grid_words[0] = uint64_t(_mm_cvtsi128_si64(_mm256_castsi256_si128(packed)));
    out.grid_words[1] = uint64_t(_mm_cvtsi128_si64(_mm256_extracti128_si256(packed, 1)));
  }
}

template <DepthFormat F>
RASTERCMP_SMALL_TARGET void evaluate_grid(const GridLanes& g, const Edge8 (&edges)[3], const Plane8& plane,
                                          const KernelDepth& depth, SmallBlockOutput& out) {
  if (g.shift == kSmallGridShift)
    evaluate_grid<F, kSmallGridShift>(g, edges, plane, depth, out);
  else
    evaluate_grid<F, 3>(g, edges, plane, depth, out);
}

// Smallest and largest lane of v.
RASTERCMP_SMALL_TARGET int min_of_lanes(__m256i m) {
  m = _mm256_min_epi32(m, _mm256_permute2x128_si256(m, m, 0x01));
  m = _mm256_min_epi32(m, _mm256_shuffle_epi32(m, 0x4E));
  m = _mm256_min_epi32(m, _mm256_shuffle_epi32(m, 0xB1));
  return _mm256_cvtsi256_si32(m);
}
RASTERCMP_SMALL_TARGET int max_of_lanes(__m256i m) {
  m = _mm256_max_epi32(m, _mm256_permute2x128_si256(m, m, 0x01));
  m = _mm256_max_epi32(m, _mm256_shuffle_epi32(m, 0x4E));
  m = _mm256_max_epi32(m, _mm256_shuffle_epi32(m, 0xB1));
  return _mm256_cvtsi256_si32(m);
}

// Largest value of v (>= 0) among the lanes set in `mask`, 0 when none is.
RASTERCMP_SMALL_TARGET int max_lane(__m256i v, __m256i mask) {
  __m256i m = _mm256_and_si256(v, mask);
  m = _mm256_max_epi32(m, _mm256_permute2x128_si256(m, m, 0x01));
  m = _mm256_max_epi32(m, _mm256_shuffle_epi32(m, 0x4E));
  m = _mm256_max_epi32(m, _mm256_shuffle_epi32(m, 0xB1));
  return _mm256_cvtsi256_si32(m);
}

// What the compositor evaluates each lane from: E - 1 at (grid_x0, y0), the steps, the plane.
RASTERCMP_SMALL_TARGET inline void store_window_lanes(const Edge8 (&edges)[3], const Plane8& plane,
                                                      SmallBlockOutput& out) {
  const __m256i ox = _mm256_set1_epi32(out.grid_x0), oy = _mm256_load_si256(reinterpret_cast<const __m256i*>(out.y0));
  for (int i = 0; i < 3; ++i) {
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.e_window[i]), edge_at(edges[i], ox, oy));
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.gx[i]), step_x(edges[i]));
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.gy[i]), step_y(edges[i]));
  }
  _mm256_store_ps(out.a0, plane.a0);
  _mm256_store_ps(out.dzdx, plane.dzdx);
  _mm256_store_ps(out.dzdy, plane.dzdy);
  out.window = true;
}

}  // namespace

#ifdef RASTERCMP_SMALL_TRAILING_PLANES
// triangle_depth_plane(window, 0.5f) of eight triangles (a, b, c), one IEEE operation per
// intrinsic: the MXCSR flags of the trailing-run check's scalar loop (render_fast.cpp), which also
// forms the plane of (a, c, b). That order raises the same flags: its differences are the first
// order's negated or exchanged (dx01' = -dx20, dy20' = -dy01, ...), its area's products are the
// first's f and e, so its area is -(e - f) and its 1/area -ooa (rounding to nearest is symmetric
// under negation), and dzdx, dzdy and a0 come out as the same roundings of the same magnitudes.
// The sign bits of every result, ORed, so that none of the arithmetic is left out.
RASTERCMP_SMALL_TARGET uint32_t RASTERCMP_SMALL_TRAILING_PLANES(const FastVertex* vertices,
                                                                const uint32_t (&corners)[3][8]) {
  const Plane8 plane = depth_plane8(load_fields(vertices, corners[0], 1), load_fields(vertices, corners[1], 1),
                                    load_fields(vertices, corners[2], 1));
  return uint32_t(_mm256_movemask_ps(_mm256_or_ps(plane.a0, _mm256_or_ps(plane.dzdx, plane.dzdy))));
}
#endif

RASTERCMP_SMALL_TARGET void RASTERCMP_SMALL_SETUP(const SmallBlockInput& in, SmallBlockOutput& out) {
  out.window = false;
  const Corners p0 = load_corners(in.vertices, in.corners[0], in.stride);
  Corners p1 = load_corners(in.vertices, in.corners[1], in.stride);
  Corners p2 = load_corners(in.vertices, in.corners[2], in.stride);
  const __m256i zero = _mm256_setzero_si256(), one = _mm256_set1_epi32(1);
  const __m256i special = _mm256_and_si256(_mm256_or_si256(p0.flags, _mm256_or_si256(p1.flags, p2.flags)),
                                           _mm256_set1_epi32(int32_t(kVertexClipBits | kVertexSnapFailed)));
  // triangle_bbox, unclipped: x0 = min >> 8, x1 = (max - 1) >> 8; then ∩ the draw region
  const __m256i bx0 = _mm256_srai_epi32(min3(p0.x_fixed, p1.x_fixed, p2.x_fixed), 8);
  const __m256i bx1 = _mm256_srai_epi32(_mm256_sub_epi32(max3(p0.x_fixed, p1.x_fixed, p2.x_fixed), one), 8);
  const __m256i by0 = _mm256_srai_epi32(min3(p0.y_fixed, p1.y_fixed, p2.y_fixed), 8);
  const __m256i by1 = _mm256_srai_epi32(_mm256_sub_epi32(max3(p0.y_fixed, p1.y_fixed, p2.y_fixed), one), 8);
  // The rectangle starts at the first column and row whose sample can be in the triangle,
  // (min + 255) >> 8 (BandWorker::triangle); `small` keeps lavapipe's box (the 32-bit bound).
  const __m256i round_up = _mm256_set1_epi32(kFixedOne - 1);
  const __m256i tx0 = _mm256_srai_epi32(_mm256_add_epi32(min3(p0.x_fixed, p1.x_fixed, p2.x_fixed), round_up), 8);
  const __m256i ty0 = _mm256_srai_epi32(_mm256_add_epi32(min3(p0.y_fixed, p1.y_fixed, p2.y_fixed), round_up), 8);
  const __m256i x0 = _mm256_max_epi32(tx0, _mm256_set1_epi32(in.region.x0));
  const __m256i x1 = _mm256_min_epi32(bx1, _mm256_set1_epi32(in.region.x1));
  const __m256i y0 = _mm256_max_epi32(ty0, _mm256_set1_epi32(in.region.y0));
  const __m256i y1 = _mm256_min_epi32(by1, _mm256_set1_epi32(in.region.y1));
  const __m256i small =
      _mm256_and_si256(_mm256_cmpgt_epi32(_mm256_set1_epi32(kSmallWidth), _mm256_sub_epi32(bx1, bx0)),
                       _mm256_cmpgt_epi32(_mm256_set1_epi32(kSmallHeight), _mm256_sub_epi32(by1, by0)));
  const __m256i simple = _mm256_and_si256(_mm256_cmpeq_epi32(special, zero), small);
  const __m256i empty = _mm256_or_si256(_mm256_cmpgt_epi32(x0, x1), _mm256_cmpgt_epi32(y0, y1));
  // area = dx01*dy20 - dx20*dy01 (§2.3), exact in 32 bits for small lanes
  const __m256i area = _mm256_sub_epi32(
      _mm256_mullo_epi32(_mm256_sub_epi32(p0.x_fixed, p1.x_fixed), _mm256_sub_epi32(p2.y_fixed, p0.y_fixed)),
      _mm256_mullo_epi32(_mm256_sub_epi32(p2.x_fixed, p0.x_fixed), _mm256_sub_epi32(p0.y_fixed, p1.y_fixed)));
  const __m256i positive = _mm256_cmpgt_epi32(area, zero);
  const __m256i front = in.front_ccw ? positive : not_mask(positive);
  const __m256i dropped =
      _mm256_or_si256(_mm256_or_si256(empty, _mm256_cmpeq_epi32(area, zero)), culled(in.cull, front));
  const uint32_t used = (1u << in.count) - 1u;
  const __m256i live = _mm256_andnot_si256(dropped, simple);
  const __m256i w = _mm256_sub_epi32(x1, x0), h = _mm256_sub_epi32(y1, y0);
  const __m256i grid_side = _mm256_set1_epi32(kGridSide);
  const __m256i grid =
      _mm256_and_si256(live, _mm256_and_si256(_mm256_cmpgt_epi32(grid_side, w), _mm256_cmpgt_epi32(grid_side, h)));
  const __m256i job = _mm256_andnot_si256(grid, live);
  out.grid_mask = lanes(grid) & used;
  out.job_mask = lanes(job) & used;
  out.scalar_mask = lanes(live) & ~out.grid_mask & ~out.job_mask & used;
  if (const uint32_t other = ~lanes(simple) & used; other != 0) [[unlikely]] {
    // The scalar set-up's first verdicts, taken here for the lanes it would drop at once: every
    // corner outside one clip plane (ClipFate::Outside), or an unclipped lane whose rectangle
    // misses the draw region (exact for every lane with its snap done, small or not).
    const __m256i not_outside =
        _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_and_si256(p0.flags, _mm256_and_si256(p1.flags, p2.flags)),
                                            _mm256_set1_epi32(int32_t(kVertexClipBits))),
                           zero);
    const uint32_t special_lanes = ~lanes(_mm256_cmpeq_epi32(special, zero));
    out.scalar_mask |= other & ((special_lanes & lanes(not_outside)) | (~special_lanes & ~lanes(empty)));
  }
  if ((out.grid_mask | out.job_mask) == 0) return;
  const __m256i swap = _mm256_cmpgt_epi32(zero, area);  // rotate_fixed_position_12: (v0, v2, v1)
  swap_where(swap, p1.x_fixed, p2.x_fixed);
  swap_where(swap, p1.y_fixed, p2.y_fixed);
  swap_where(swap, p1.x, p2.x);
  swap_where(swap, p1.y, p2.y);
  swap_where(swap, p1.z, p2.z);
  const Plane8 plane = in.depth.format != DepthFormat::None ? depth_plane8(p0, p1, p2) : Plane8{};
  const Edge8 edges[3] = {edge8(p0.x_fixed, p0.y_fixed, p1.x_fixed, p1.y_fixed),
                          edge8(p1.x_fixed, p1.y_fixed, p2.x_fixed, p2.y_fixed),
                          edge8(p2.x_fixed, p2.y_fixed, p0.x_fixed, p0.y_fixed)};
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.x0), x0);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.y0), y0);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.x1), x1);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.y1), y1);
  if (out.grid_mask) {
    const int columns = max_lane(w, grid) + 1, rows = max_lane(h, grid) + 1;
    const int shift = columns <= kSmallGridSide && rows <= kSmallGridSide ? kSmallGridShift : 3;
    const GridLanes g{grid, x0, y0, w, h, columns, rows, shift};
    out.grid_shift = shift;
    // The union of the grid lanes' rectangles (lanes past in.count repeat a lane's primitive, so
    // they add nothing to it).
    const __m256i none_low = _mm256_set1_epi32(INT32_MAX), none_high = _mm256_set1_epi32(INT32_MIN);
    out.grid_x0 = min_of_lanes(_mm256_blendv_epi8(none_low, x0, grid));
    out.grid_y0 = min_of_lanes(_mm256_blendv_epi8(none_low, y0, grid));
    out.grid_x1 = max_of_lanes(_mm256_blendv_epi8(none_high, x1, grid));
    out.grid_y1 = max_of_lanes(_mm256_blendv_epi8(none_high, y1, grid));
    if (in.window_ok && goes_to_window(out, shift)) {
      store_window_lanes(edges, plane, out);
      return;
    }
    with_depth_format(in.depth.format, [&]<DepthFormat F>() RASTERCMP_SMALL_TARGET {
      evaluate_grid<F>(g, edges, plane, in.depth, out);
    });
  }
  if (out.job_mask) {
    // spans = w / 8 + 1 8-lane spans per row from origin_x (at most eight), ending in x1's tile:
    // origin_x = min(x0, end of x1's tile + 1 - 8 * spans), so x1 <= origin_x + 8 * spans - 1 <= that
    // end. A lane across a tile border starts at x0.
    const __m256i last_start =
        _mm256_sub_epi32(_mm256_or_si256(x1, _mm256_set1_epi32(kTileSize - 1)),
                         _mm256_add_epi32(_mm256_and_si256(w, _mm256_set1_epi32(~7)), _mm256_set1_epi32(7)));
    const __m256i origin_x = _mm256_min_epi32(x0, last_start);
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.origin_x), origin_x);
    _mm256_store_ps(out.a0, plane.a0);
    _mm256_store_ps(out.dzdx, plane.dzdx);
    _mm256_store_ps(out.dzdy, plane.dzdy);
    store_job_edges(edges, origin_x, y0, out);
  }
}

}  // namespace rastercmp::cpu::fast
