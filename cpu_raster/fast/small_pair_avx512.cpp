// The sixteen-wide set-up of small triangles (AVX-512 hosts, small_triangles.hpp): two blocks of
// a draw in the sixteen lanes of the zmm registers, lanes 0-7 the first block's, 8-15 the
// second's. Every operation is the eight-wide set-up's (small_setup_simd.inl), lane for lane, so
// each block's output describes the same triangles, pixels and raw depths as
// setup_small_block_avx512 gives it; the only freedom taken is the grid layout, which is the
// wider one of the two blocks when they differ (test FastSmallTriangles.PairSetupEqualsTwoBlocks).
#include <immintrin.h>

#include <algorithm>

#include "cpu_raster/fast/avx512_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"
#include "cpu_raster/fast/small_triangles.hpp"

namespace rastercmp::cpu::fast {
namespace {

using Lanes = __mmask16;  // bit l: lane l (block 0's lane l, or block 1's lane l - 8)

struct Corners16 {  // one triangle corner of sixteen lanes
  __m512i x_fixed, y_fixed, flags;
  __m512 x, y, z;
};

RASTERCMP_AVX512 inline __m512i splat(int32_t v) { return _mm512_set1_epi32(v); }

// snap_fixed8 on sixteen lanes.
RASTERCMP_AVX512 inline __m512i snap_fixed16(__m512 c) {
  return _mm512_cvtps_epi32(_mm512_mul_ps(_mm512_sub_ps(c, _mm512_set1_ps(0.5f)), _mm512_set1_ps(256.0f)));
}

inline const float* corner(const SmallBlockInput& in, int k, uint32_t lane) {
  return reinterpret_cast<const float*>(in.vertices + in.corners[k][lane * in.stride]);
}

// Corner k of both blocks' lanes: sixteen FastVertex (a 4x16 transpose, load_corners' steps on
// four 128-bit quarters: lanes q, q + 4, q + 8, q + 12 in register q), and the snap.
RASTERCMP_AVX512 inline Corners16 load_corners16(const SmallBlockInput& in0, const SmallBlockInput& in1, int k) {
  __m512 r[4];
  for (uint32_t q = 0; q < 4; ++q) {
    __m512 v = _mm512_castps128_ps512(_mm_loadu_ps(corner(in0, k, q)));
    v = _mm512_insertf32x4(v, _mm_loadu_ps(corner(in0, k, q + 4)), 1);
    v = _mm512_insertf32x4(v, _mm_loadu_ps(corner(in1, k, q)), 2);
    r[q] = _mm512_insertf32x4(v, _mm_loadu_ps(corner(in1, k, q + 4)), 3);
  }
  const __m512 t0 = _mm512_unpacklo_ps(r[0], r[1]), t1 = _mm512_unpackhi_ps(r[0], r[1]);  // x0 x1 y0 y1, z0 z1 f0 f1
  const __m512 t2 = _mm512_unpacklo_ps(r[2], r[3]), t3 = _mm512_unpackhi_ps(r[2], r[3]);
  Corners16 c;
  c.x = _mm512_shuffle_ps(t0, t2, 0x44);
  c.y = _mm512_shuffle_ps(t0, t2, 0xEE);
  c.z = _mm512_shuffle_ps(t1, t3, 0x44);
  c.flags = _mm512_castps_si512(_mm512_shuffle_ps(t1, t3, 0xEE));
  c.x_fixed = snap_fixed16(c.x);
  c.y_fixed = snap_fixed16(c.y);
  return c;
}

RASTERCMP_AVX512 inline __m512i min3(__m512i a, __m512i b, __m512i c) {
  return _mm512_min_epi32(a, _mm512_min_epi32(b, c));
}
RASTERCMP_AVX512 inline __m512i max3(__m512i a, __m512i b, __m512i c) {
  return _mm512_max_epi32(a, _mm512_max_epi32(b, c));
}

RASTERCMP_AVX512 inline void swap_where(Lanes swap, __m512i& a, __m512i& b) {
  const __m512i na = _mm512_mask_blend_epi32(swap, a, b), nb = _mm512_mask_blend_epi32(swap, b, a);
  a = na;
  b = nb;
}
RASTERCMP_AVX512 inline void swap_where(Lanes swap, __m512& a, __m512& b) {
  const __m512 na = _mm512_mask_blend_ps(swap, a, b), nb = _mm512_mask_blend_ps(swap, b, a);
  a = na;
  b = nb;
}

// The faces the cull mode drops, given which lanes are front-facing.
inline Lanes culled(CullMode cull, Lanes front) {
  switch (cull) {
    case CullMode::None: return 0;
    case CullMode::Front: return front;
    case CullMode::Back: return Lanes(~front);
    case CullMode::FrontAndBack: return Lanes(0xFFFF);
  }
  return 0;
}

struct Plane16 {
  __m512 a0, dzdx, dzdy;
};

// depth_plane8 (triangle_depth_plane(window, 0.5f)) on sixteen lanes.
RASTERCMP_AVX512 inline Plane16 depth_plane16(const Corners16& p0, const Corners16& p1, const Corners16& p2) {
  const __m512 half = _mm512_set1_ps(0.5f);
  const __m512 x0_center = _mm512_sub_ps(p0.x, half), y0_center = _mm512_sub_ps(p0.y, half);
  const __m512 dx01 = _mm512_sub_ps(p0.x, p1.x), dy01 = _mm512_sub_ps(p0.y, p1.y);
  const __m512 dx20 = _mm512_sub_ps(p2.x, p0.x), dy20 = _mm512_sub_ps(p2.y, p0.y);
  const __m512 e = _mm512_mul_ps(dx01, dy20), f = _mm512_mul_ps(dy01, dx20);
  const __m512 ooa = _mm512_div_ps(_mm512_set1_ps(1.0f), _mm512_sub_ps(e, f));
  const __m512 dx20_ooa = _mm512_mul_ps(dx20, ooa), dy20_ooa = _mm512_mul_ps(dy20, ooa);
  const __m512 dx01_ooa = _mm512_mul_ps(dx01, ooa), dy01_ooa = _mm512_mul_ps(dy01, ooa);
  const __m512 dz01 = _mm512_sub_ps(p0.z, p1.z), dz20 = _mm512_sub_ps(p2.z, p0.z);
  Plane16 plane;
  plane.dzdx = _mm512_sub_ps(_mm512_mul_ps(dz01, dy20_ooa), _mm512_mul_ps(dz20, dy01_ooa));
  plane.dzdy = _mm512_sub_ps(_mm512_mul_ps(dz20, dx01_ooa), _mm512_mul_ps(dz01, dx20_ooa));
  plane.a0 =
      _mm512_sub_ps(p0.z, _mm512_add_ps(_mm512_mul_ps(plane.dzdx, x0_center), _mm512_mul_ps(plane.dzdy, y0_center)));
  return plane;
}

// edge8 on sixteen lanes: dcdx = y_i - y_j, dcdy = x_i - x_j, bias_minus_1 0 on inclusive
// (top-left, §2.4) edges and -1 otherwise.
struct Edge16 {
  __m512i xi, yi, dcdx, dcdy, bias_minus_1;
};

RASTERCMP_AVX512 inline Edge16 edge16(__m512i xi, __m512i yi, __m512i xj, __m512i yj) {
  const __m512i zero = _mm512_setzero_si512();
  Edge16 e{xi, yi, _mm512_sub_epi32(yi, yj), _mm512_sub_epi32(xi, xj), zero};
  const Lanes inclusive = _mm512_cmplt_epi32_mask(e.dcdx, zero) |
                          (_mm512_cmpeq_epi32_mask(e.dcdx, zero) & _mm512_cmpgt_epi32_mask(e.dcdy, zero));
  e.bias_minus_1 = _mm512_mask_blend_epi32(inclusive, splat(-1), zero);
  return e;
}

// E - 1 at pixel (ox, oy) (edge_at).
RASTERCMP_AVX512 inline __m512i edge_at(const Edge16& e, __m512i ox, __m512i oy) {
  const __m512i v = _mm512_sub_epi32(_mm512_mullo_epi32(e.dcdx, _mm512_sub_epi32(e.xi, _mm512_slli_epi32(ox, 8))),
                                     _mm512_mullo_epi32(e.dcdy, _mm512_sub_epi32(e.yi, _mm512_slli_epi32(oy, 8))));
  return _mm512_add_epi32(v, e.bias_minus_1);
}
RASTERCMP_AVX512 inline __m512i step_x(const Edge16& e) {
  return _mm512_slli_epi32(_mm512_sub_epi32(_mm512_setzero_si512(), e.dcdx), 8);
}
RASTERCMP_AVX512 inline __m512i step_y(const Edge16& e) { return _mm512_slli_epi32(e.dcdy, 8); }

// Lanes 0-7 of v to block 0's array, lanes 8-15 to block 1's.
RASTERCMP_AVX512 inline void store_halves(int32_t* lo, int32_t* hi, __m512i v) {
  _mm256_store_si256(reinterpret_cast<__m256i*>(lo), _mm512_castsi512_si256(v));
  _mm256_store_si256(reinterpret_cast<__m256i*>(hi), _mm512_extracti64x4_epi64(v, 1));
}
RASTERCMP_AVX512 inline void store_halves(uint32_t* lo, uint32_t* hi, __m512i v) {
  store_halves(reinterpret_cast<int32_t*>(lo), reinterpret_cast<int32_t*>(hi), v);
}
RASTERCMP_AVX512 inline void store_halves(float* lo, float* hi, __m512 v) {
  store_halves(reinterpret_cast<int32_t*>(lo), reinterpret_cast<int32_t*>(hi), _mm512_castps_si512(v));
}

struct Pair {
  SmallBlockOutput* out[2];
};

constexpr Lanes kHalf[2] = {0x00FF, 0xFF00};

inline uint32_t half_bits(Lanes m, int h) { return (uint32_t(m) >> (8 * h)) & 0xFFu; }

struct GridLanes16 {
  Lanes mask;                // the lanes evaluated
  __m512i x0, y0, w, h;      // w, h: rectangle width and height minus 1
  int columns, rows, shift;  // the largest over the evaluated lanes; the common bit layout
};

// evaluate_grid on sixteen lanes: coverage bits and raw depth of every candidate pixel, each
// block's half stored in its own output.
template <DepthFormat F, int Shift>
RASTERCMP_AVX512 void evaluate_grid16(const GridLanes16& g, const Edge16 (&edges)[3], const Plane16& plane,
                                      const Depth16& depth, const Pair& pair) {
  const int columns = g.columns, rows = g.rows;
  __m512i row_e[3], gx[3], gy[3];
  for (int i = 0; i < 3; ++i) {
    row_e[i] = edge_at(edges[i], g.x0, g.y0);
    gx[i] = step_x(edges[i]);
    gy[i] = step_y(edges[i]);
  }
  __m512i column_bit[kGridSide];  // bit dx in the lanes whose rectangle reaches column dx
  __m512 inner[kGridSide];        // FMA?(dzdx, px, a0), which depends on the column only
  for (int dx = 0; dx < columns; ++dx) {
    column_bit[dx] = _mm512_maskz_mov_epi32(_mm512_cmpge_epi32_mask(g.w, splat(dx)), splat(1 << dx));
    if constexpr (F != DepthFormat::None) {
      const __m512 px = _mm512_cvtepi32_ps(_mm512_add_epi32(g.x0, splat(dx)));
      inner[dx] = mul_add16(plane.dzdx, px, plane.a0, depth.fma);
    }
  }
  __m512i bits_lo = _mm512_setzero_si512(), bits_hi = _mm512_setzero_si512();  // positions 0-31, 32-63
  for (int dy = 0; dy < rows; ++dy) {
    const Lanes in_y = g.mask & _mm512_cmpge_epi32_mask(g.h, splat(dy));
    const __m512 py = _mm512_cvtepi32_ps(_mm512_add_epi32(g.y0, splat(dy)));
    __m512i e[3] = {row_e[0], row_e[1], row_e[2]};
    __m512i row_bits = _mm512_setzero_si512();
    for (int dx = 0; dx < columns; ++dx) {
      // covered: every E - 1 >= 0, i.e. the sign bit of e0 | e1 | e2 clear
      const Lanes covered =
          _mm512_cmpge_epi32_mask(_mm512_ternarylogic_epi32(e[0], e[1], e[2], 0xFE), _mm512_setzero_si512());
      row_bits = _mm512_mask_or_epi32(row_bits, covered, row_bits, column_bit[dx]);
      if constexpr (F != DepthFormat::None) {
        const int p = (dy << Shift) + dx;
        const __m512i raw = to_raw16<F>(finish_depth16(mul_add16(plane.dzdy, py, inner[dx], depth.fma), depth));
        store_halves(pair.out[0]->grid_raw[p], pair.out[1]->grid_raw[p], raw);
      }
      for (int i = 0; i < 3; ++i) e[i] = _mm512_add_epi32(e[i], gx[i]);
    }
    const int p0 = dy << Shift;  // the row's first position
    const __m512i placed = _mm512_sll_epi32(_mm512_maskz_mov_epi32(in_y, row_bits), _mm_cvtsi32_si128(p0 & 31));
    if (p0 < 32)
      bits_lo = _mm512_or_si512(bits_lo, placed);
    else
      bits_hi = _mm512_or_si512(bits_hi, placed);
    for (int i = 0; i < 3; ++i) row_e[i] = _mm512_add_epi32(row_e[i], gy[i]);
  }
  // grid_bits[l] = lo[l] | hi[l] << 32: unpack gives lanes (4c, 4c + 1) and (4c + 2, 4c + 3) of
  // quarter c as 64-bit lanes; two permutes put them in lane order, block by block.
  const __m512i lo = _mm512_unpacklo_epi32(bits_lo, bits_hi), hi = _mm512_unpackhi_epi32(bits_lo, bits_hi);
  _mm512_storeu_si512(pair.out[0]->grid_bits,
                      _mm512_permutex2var_epi64(lo, _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11), hi));
  _mm512_storeu_si512(pair.out[1]->grid_bits,
                      _mm512_permutex2var_epi64(lo, _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15), hi));
  if constexpr (Shift == kSmallGridShift) {  // 16 bits per lane, four lanes to a word (bits < 2^16: vpmovdw keeps them)
    const __m256i packed = _mm512_cvtepi32_epi16(bits_lo);
    const __m128i words0 = _mm256_castsi256_si128(packed), words1 = _mm256_extracti128_si256(packed, 1);
    pair.out[0]->grid_words[0] = uint64_t(_mm_cvtsi128_si64(words0));
    pair.out[0]->grid_words[1] = uint64_t(_mm_extract_epi64(words0, 1));
    pair.out[1]->grid_words[0] = uint64_t(_mm_cvtsi128_si64(words1));
    pair.out[1]->grid_words[1] = uint64_t(_mm_extract_epi64(words1, 1));
  }
}

template <DepthFormat F>
RASTERCMP_AVX512 void evaluate_grid16(const GridLanes16& g, const Edge16 (&edges)[3], const Plane16& plane,
                                      const Depth16& depth, const Pair& pair) {
  if (g.shift == kSmallGridShift)
    evaluate_grid16<F, kSmallGridShift>(g, edges, plane, depth, pair);
  else
    evaluate_grid16<F, 3>(g, edges, plane, depth, pair);
}

// One block's grid lanes (`grid`: lanes of its half only): the union of their rectangles (the
// grid_x0.. fields), and the columns and rows their own layout would take.
RASTERCMP_AVX512 void measure_grid_half(Lanes grid, __m512i x0, __m512i y0, __m512i x1, __m512i y1, __m512i w,
                                        __m512i h, SmallBlockOutput& out, int& columns, int& rows) {
  out.grid_x0 = _mm512_mask_reduce_min_epi32(grid, x0);
  out.grid_y0 = _mm512_mask_reduce_min_epi32(grid, y0);
  out.grid_x1 = _mm512_mask_reduce_max_epi32(grid, x1);
  out.grid_y1 = _mm512_mask_reduce_max_epi32(grid, y1);
  columns = _mm512_mask_reduce_max_epi32(grid, w) + 1;
  rows = _mm512_mask_reduce_max_epi32(grid, h) + 1;
}

}  // namespace

RASTERCMP_AVX512 void setup_small_pair_avx512(const SmallBlockInput& in0, const SmallBlockInput& in1,
                                              SmallBlockOutput& out0, SmallBlockOutput& out1) {
  const Pair pair{{&out0, &out1}};
  out0.window = out1.window = false;
  const Corners16 p0 = load_corners16(in0, in1, 0);
  Corners16 p1 = load_corners16(in0, in1, 1);
  Corners16 p2 = load_corners16(in0, in1, 2);
  const __m512i zero = _mm512_setzero_si512(), one = splat(1);
  const Lanes special = _mm512_test_epi32_mask(_mm512_ternarylogic_epi32(p0.flags, p1.flags, p2.flags, 0xFE),
                                               splat(int32_t(kVertexClipBits | kVertexSnapFailed)));
  // triangle_bbox, unclipped: x0 = min >> 8, x1 = (max - 1) >> 8; then ∩ the draw region
  const __m512i bx0 = _mm512_srai_epi32(min3(p0.x_fixed, p1.x_fixed, p2.x_fixed), 8);
  const __m512i bx1 = _mm512_srai_epi32(_mm512_sub_epi32(max3(p0.x_fixed, p1.x_fixed, p2.x_fixed), one), 8);
  const __m512i by0 = _mm512_srai_epi32(min3(p0.y_fixed, p1.y_fixed, p2.y_fixed), 8);
  const __m512i by1 = _mm512_srai_epi32(_mm512_sub_epi32(max3(p0.y_fixed, p1.y_fixed, p2.y_fixed), one), 8);
  const PixelRect& region = in0.region;
  // The rectangle starts at the first column and row whose sample can be in the triangle,
  // (min + 255) >> 8 (BandWorker::triangle); `small` keeps lavapipe's box (the 32-bit bound).
  const __m512i tx0 =
      _mm512_srai_epi32(_mm512_add_epi32(min3(p0.x_fixed, p1.x_fixed, p2.x_fixed), splat(kFixedOne - 1)), 8);
  const __m512i ty0 =
      _mm512_srai_epi32(_mm512_add_epi32(min3(p0.y_fixed, p1.y_fixed, p2.y_fixed), splat(kFixedOne - 1)), 8);
  const __m512i x0 = _mm512_max_epi32(tx0, splat(region.x0)), x1 = _mm512_min_epi32(bx1, splat(region.x1));
  const __m512i y0 = _mm512_max_epi32(ty0, splat(region.y0)), y1 = _mm512_min_epi32(by1, splat(region.y1));
  const Lanes small = _mm512_cmplt_epi32_mask(_mm512_sub_epi32(bx1, bx0), splat(kSmallWidth)) &
                      _mm512_cmplt_epi32_mask(_mm512_sub_epi32(by1, by0), splat(kSmallHeight));
  const Lanes simple = Lanes(~special & small);
  const Lanes empty = _mm512_cmpgt_epi32_mask(x0, x1) | _mm512_cmpgt_epi32_mask(y0, y1);
  // area = dx01*dy20 - dx20*dy01 (§2.3), exact in 32 bits for small lanes
  const __m512i area = _mm512_sub_epi32(
      _mm512_mullo_epi32(_mm512_sub_epi32(p0.x_fixed, p1.x_fixed), _mm512_sub_epi32(p2.y_fixed, p0.y_fixed)),
      _mm512_mullo_epi32(_mm512_sub_epi32(p2.x_fixed, p0.x_fixed), _mm512_sub_epi32(p0.y_fixed, p1.y_fixed)));
  const Lanes positive = _mm512_cmpgt_epi32_mask(area, zero);
  const Lanes front = in0.front_ccw ? positive : Lanes(~positive);
  const Lanes dropped = empty | _mm512_cmpeq_epi32_mask(area, zero) | culled(in0.cull, front);
  const Lanes used = Lanes(((1u << in0.count) - 1u) | (((1u << in1.count) - 1u) << 8));
  const Lanes live = Lanes(simple & ~dropped);
  const __m512i w = _mm512_sub_epi32(x1, x0), h = _mm512_sub_epi32(y1, y0);
  const Lanes grid =
      live & _mm512_cmplt_epi32_mask(w, splat(kGridSide)) & _mm512_cmplt_epi32_mask(h, splat(kGridSide)) & used;
  const Lanes job = Lanes(live & ~grid & used);
  // The scalar set-up's first verdicts for the lanes it would drop at once (small_setup_simd.inl).
  const Lanes outside = _mm512_test_epi32_mask(_mm512_ternarylogic_epi32(p0.flags, p1.flags, p2.flags, 0x80),
                                               splat(int32_t(kVertexClipBits)));
  const Lanes scalar = Lanes(((special & ~outside) | (~special & ~small & ~empty) | (live & ~grid & ~job)) & used);
  for (int b = 0; b < 2; ++b) {
    pair.out[b]->grid_mask = half_bits(grid, b);
    pair.out[b]->job_mask = half_bits(job, b);
    pair.out[b]->scalar_mask = half_bits(scalar, b);
  }
  if ((grid | job) == 0) return;
  const Lanes swap = _mm512_cmplt_epi32_mask(area, zero);  // rotate_fixed_position_12: (v0, v2, v1)
  swap_where(swap, p1.x_fixed, p2.x_fixed);
  swap_where(swap, p1.y_fixed, p2.y_fixed);
  swap_where(swap, p1.x, p2.x);
  swap_where(swap, p1.y, p2.y);
  swap_where(swap, p1.z, p2.z);
  const Plane16 plane = in0.depth.format != DepthFormat::None ? depth_plane16(p0, p1, p2) : Plane16{};
  const Edge16 edges[3] = {edge16(p0.x_fixed, p0.y_fixed, p1.x_fixed, p1.y_fixed),
                           edge16(p1.x_fixed, p1.y_fixed, p2.x_fixed, p2.y_fixed),
                           edge16(p2.x_fixed, p2.y_fixed, p0.x_fixed, p0.y_fixed)};
  store_halves(out0.x0, out1.x0, x0);
  store_halves(out0.y0, out1.y0, y0);
  store_halves(out0.x1, out1.x1, x1);
  store_halves(out0.y1, out1.y1, y1);
  // Per block: its grid lanes' union and own layout; the window blocks (in.window_ok) and the
  // blocks whose grid lanes are evaluated here, in the layout wide enough for all of them.
  Lanes evaluated = 0, window = 0;
  int columns = 0, rows = 0;
  bool small_layout = true;
  for (int b = 0; b < 2; ++b) {
    SmallBlockOutput& out = *pair.out[b];
    if (out.grid_mask == 0) continue;
    int block_columns = 0, block_rows = 0;
    measure_grid_half(grid & kHalf[b], x0, y0, x1, y1, w, h, out, block_columns, block_rows);
    const int shift = block_columns <= kSmallGridSide && block_rows <= kSmallGridSide ? kSmallGridShift : 3;
    out.grid_shift = shift;
    if (in0.window_ok && goes_to_window(out, shift)) {
      out.window = true;
      window |= kHalf[b];
      continue;
    }
    evaluated |= grid & kHalf[b];
    columns = std::max(columns, block_columns);
    rows = std::max(rows, block_rows);
    small_layout = small_layout && shift == kSmallGridShift;
  }
  if (evaluated) {
    const int shift = small_layout ? kSmallGridShift : 3;
    for (int b = 0; b < 2; ++b)
      if (evaluated & kHalf[b]) pair.out[b]->grid_shift = shift;
    const GridLanes16 g{evaluated, x0, y0, w, h, columns, rows, shift};
    const Depth16 depth = depth16(in0.depth);
    with_depth_format(in0.depth.format,
                      [&]<DepthFormat F>() RASTERCMP_AVX512 { evaluate_grid16<F>(g, edges, plane, depth, pair); });
  }
  if ((job | window) == 0) return;
  // What the kernel jobs and the window compositor evaluate each lane from: the steps, the plane,
  // E - 1 at the job's origin (origin_x, y0) or at the window's column grid_x0 of row y0.
  for (int i = 0; i < 3; ++i) {
    store_halves(out0.gx[i], out1.gx[i], step_x(edges[i]));
    store_halves(out0.gy[i], out1.gy[i], step_y(edges[i]));
  }
  store_halves(out0.a0, out1.a0, plane.a0);
  store_halves(out0.dzdx, out1.dzdx, plane.dzdx);
  store_halves(out0.dzdy, out1.dzdy, plane.dzdy);
  if (job) {  // w / 8 + 1 spans per row from origin_x, ending in x1's tile (small_setup_simd.inl)
    const __m512i last_start = _mm512_sub_epi32(_mm512_or_si512(x1, splat(kTileSize - 1)),
                                                _mm512_add_epi32(_mm512_and_si512(w, splat(~7)), splat(7)));
    const __m512i origin_x = _mm512_min_epi32(x0, last_start);
    store_halves(out0.origin_x, out1.origin_x, origin_x);
    for (int i = 0; i < 3; ++i) store_halves(out0.g_minus_1[i], out1.g_minus_1[i], edge_at(edges[i], origin_x, y0));
  }
  if (window) {
    const __m512i ox = _mm512_mask_blend_epi32(kHalf[1], splat(out0.grid_x0), splat(out1.grid_x0));
    for (int i = 0; i < 3; ++i) store_halves(out0.e_window[i], out1.e_window[i], edge_at(edges[i], ox, y0));
  }
}

}  // namespace rastercmp::cpu::fast
