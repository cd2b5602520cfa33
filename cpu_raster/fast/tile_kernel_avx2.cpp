// AVX2 kernels of tile_kernel.hpp, one per depth format and compare op. Each lane does exactly
// the scalar exact path's IEEE operations (depth_sample.cpp), so the bits agree lane by lane:
// _mm256_min_ps / _mm256_max_ps return their second operand on NaN, as sse_min / sse_max do;
// the float compares use the unordered predicates of docs/lavapipe-rules.md §3.6; UNORM depth stays
// below 2^24, so a signed 32-bit compare orders it as the unsigned one does.
#include <immintrin.h>

#include <array>
#include <utility>

#include <algorithm>

#include "cpu_raster/fast/avx2_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"
#include "cpu_raster/fast/row_columns_avx2.hpp"
#include "cpu_raster/fast/small_triangles.hpp"
#include "cpu_raster/fast/tile_depth_bounds.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"

namespace rastercmp::cpu::fast {
namespace {

RASTERCMP_AVX2 inline __m256i load_lanes(const uint32_t* p, __m256i in_row, bool row_end) {
  if (row_end) return _mm256_maskload_epi32(reinterpret_cast<const int*>(p), in_row);
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}

// Writes `value` where `pass` is set. Lanes past the row's end are never touched (maskstore); the
// others belong to this tile, which only this thread writes, so a blended full store is safe.
RASTERCMP_AVX2 inline void store_lanes(uint32_t* p, __m256i value, __m256i old, __m256i pass, bool row_end) {
  if (row_end) {
    _mm256_maskstore_epi32(reinterpret_cast<int*>(p), pass, value);
  } else {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), _mm256_blendv_epi8(old, value, pass));
  }
}

RASTERCMP_AVX2 inline bool all_lanes(__m256i mask) { return _mm256_movemask_ps(_mm256_castsi256_ps(mask)) == 0xFF; }

// A rectangle every pixel of which is covered, in whole 8-pixel spans inside the row: no edge
// or column masks, and the inner FMA?(dzdx, px, a0) of each of the tile's columns computed once.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool covered_spans(const KernelJob& j, const KernelDepth& d, const TileTarget& t) {
  constexpr int kMaxSpans = 8;  // a tile row is 64 pixels
  const int spans = (j.rect.x1 + 1 - j.rect.x0) / 8;
  const __m256 lane = _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7);
  __m256 inner[kMaxSpans];
  for (int k = 0; k < spans; ++k) {
    const __m256 px = _mm256_add_ps(_mm256_set1_ps(float(j.rect.x0 + 8 * k)), lane);  // exact: integers below 2^24
    inner[k] = mul_add8(_mm256_set1_ps(j.dzdx), px, _mm256_set1_ps(j.a0), d.fma);
  }
  const __m256 dzdy = _mm256_set1_ps(j.dzdy), offset = _mm256_set1_ps(j.offset);
  const __m256i owner = _mm256_set1_epi32(int32_t(j.owner)), all = _mm256_set1_epi32(-1);
  bool any = false;
  for (int32_t y = j.rect.y0; y <= j.rect.y1; ++y) {
    const __m256 py = _mm256_set1_ps(float(y));
    uint32_t* owner_row = t.owner + size_t(y) * size_t(t.width) + size_t(j.rect.x0);
    uint32_t* depth_row = F != DepthFormat::None ? t.depth + size_t(y) * size_t(t.width) + size_t(j.rect.x0) : nullptr;
    for (int k = 0; k < spans; ++k) {
      __m256i pass = all;
      if constexpr (F != DepthFormat::None) {
        const __m256 z = finish_depth8(mul_add8(dzdy, py, inner[k], d.fma), offset, d);
        const __m256i raw = to_raw<F>(z);
        __m256i* depth_span = reinterpret_cast<__m256i*>(depth_row + 8 * k);
        if constexpr (Op == CompareOp::Always) {
          if (d.write) _mm256_storeu_si256(depth_span, raw);
        } else {
          const __m256i stored = _mm256_loadu_si256(depth_span);
          pass = depth_passes<F, Op>(z, raw, stored);
          if (_mm256_testz_si256(pass, pass)) continue;
          if (d.write) _mm256_storeu_si256(depth_span, _mm256_blendv_epi8(stored, raw, pass));
        }
      }
      __m256i* owner_span = reinterpret_cast<__m256i*>(owner_row + 8 * k);
      if (all_lanes(pass))
        _mm256_storeu_si256(owner_span, owner);
      else
        _mm256_storeu_si256(owner_span, _mm256_blendv_epi8(_mm256_loadu_si256(owner_span), owner, pass));
      any = true;
    }
  }
  return any;
}

// A job's depth plane and state in locals, read once per job: the kernels store through
// may_alias vector pointers, so fields read through the job or the KernelDepth are reloaded after
// every store otherwise.
struct SpanDepth {
  __m256 a0, dzdx, dzdy, offset, zmin, zmax;
  bool fma, clamp, write;
};

RASTERCMP_AVX2 inline SpanDepth span_depth(const KernelJob& j, const KernelDepth& d) {
  return SpanDepth{_mm256_set1_ps(j.a0),     _mm256_set1_ps(j.dzdx), _mm256_set1_ps(j.dzdy),
                   _mm256_set1_ps(j.offset), _mm256_set1_ps(d.zmin), _mm256_set1_ps(d.zmax),
                   d.fma,                    d.clamp,                d.write};
}

// z = fl(FMA?(dzdy, py, inner) + o), then min(z, 1), max(z, 0) and the depth clamp (finish_depth8's
// operations), with inner = FMA?(dzdx, px, a0) (span_z), which depends on the columns only.
RASTERCMP_AVX2 inline __m256 span_z_inner(const SpanDepth& s, __m256 inner, __m256 py) {
  __m256 z = _mm256_add_ps(mul_add8(s.dzdy, py, inner, s.fma), s.offset);
  z = _mm256_max_ps(_mm256_min_ps(z, _mm256_set1_ps(1.0f)), _mm256_setzero_ps());
  if (s.clamp) z = _mm256_max_ps(_mm256_min_ps(z, s.zmax), s.zmin);
  return z;
}
RASTERCMP_AVX2 inline __m256 span_z(const SpanDepth& s, __m256 px, __m256 py) {
  return span_z_inner(s, mul_add8(s.dzdx, px, s.a0, s.fma), py);
}

// One span of row_spans whose coverage is known: depth test and writes, then the owner. Lanes
// past the row's end (row_end) are never touched; the others lie in this worker's tile row.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 inline bool write_covered(const SpanDepth& s, uint32_t* depth, uint32_t* owner_px, __m256i xv,
                                         __m256 py, __m256i covered, __m256i owner, bool row_end,
                                         __m256i in_row) {
  __m256i pass = covered;
  if constexpr (F != DepthFormat::None) {
    const __m256 z = span_z(s, _mm256_cvtepi32_ps(xv), py);
    const __m256i raw = to_raw<F>(z);
    const __m256i stored = row_end || Op != CompareOp::Always || !all_lanes(covered) ? load_lanes(depth, in_row, row_end)
                                                                                     : _mm256_setzero_si256();
    if constexpr (Op != CompareOp::Always) {
      pass = _mm256_and_si256(pass, depth_passes<F, Op>(z, raw, stored));
      if (_mm256_testz_si256(pass, pass)) return false;
    }
    if (s.write) store_lanes(depth, raw, stored, pass, row_end);
  }
  if (!row_end && all_lanes(pass)) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(owner_px), owner);
  } else {
    store_lanes(owner_px, owner, load_lanes(owner_px, in_row, row_end), pass, row_end);
  }
  return true;
}

// Mid-size triangles (rectangles wider than one span): per row the covered columns from the edges
// (row_columns_avx2.hpp), then whole 8-pixel spans from the first of them, the last span masked:
// no edge values per span, and the spans of an 8-60 px triangle mostly full instead of a third
// full over its rectangle. A span that would reach past the end of the tile of the rectangle's
// last column, or past the row's end, takes masked loads and stores: the next tile may be another
// worker's (TileState::worker), and a blended store there would write back what it read.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool row_spans(const KernelJob& j, const KernelDepth& d, const TileTarget& t) {
  const SpanDepth s = span_depth(j, d);
  const int32_t limit = std::min(t.width, (j.rect.x1 | (kTileSize - 1)) + 1);  // columns below it are ours
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), all = _mm256_set1_epi32(-1);
  const __m256i owner = _mm256_set1_epi32(int32_t(j.owner)), row_width = _mm256_set1_epi32(limit);
  const int32_t last_full = limit - 8;
  uint32_t* const owner_base = t.owner;
  uint32_t* const depth_base = t.depth;
  const size_t width = size_t(t.width);
  bool any = false;
  CoveredRows rows;
  init_covered_rows(rows, j);
  int32_t y, x, x_end;
  while (rows.next(y, x, x_end)) {
    const __m256 py = _mm256_set1_ps(float(y));
    const size_t row = size_t(y) * width;
    for (; x + 7 <= x_end; x += 8) {
      const __m256i xv = _mm256_add_epi32(_mm256_set1_epi32(x), lane);
      const bool row_end = x > last_full;
      any |= write_covered<F, Op>(s, F != DepthFormat::None ? depth_base + row + x : nullptr, owner_base + row + x,
                                  xv, py, all, owner, row_end, row_end ? _mm256_cmpgt_epi32(row_width, xv) : all);
    }
    if (x > x_end) continue;
    const __m256i xv = _mm256_add_epi32(_mm256_set1_epi32(x), lane);
    const __m256i covered = _mm256_cmpgt_epi32(_mm256_set1_epi32(x_end + 1), xv);
    const bool row_end = x > last_full;
    any |= write_covered<F, Op>(s, F != DepthFormat::None ? depth_base + row + x : nullptr, owner_base + row + x, xv,
                                py, covered, owner, row_end, row_end ? _mm256_cmpgt_epi32(row_width, xv) : covered);
  }
  return any;
}

// Jobs of at most kNarrowSpans spans (32 columns, narrow16's two steps) from origin_x: per row
// each span's edges' G - 1 (32-bit, stepped by gy from row to row, as the loop below: at most 7
// columns past the rectangle), covered where all three are >= 0 and the column lies in the
// rectangle, then the depth test and writes of the span whatever its coverage: no division per
// edge and four rows (the covered columns of row_spans) and no branch on the data, as narrow16 on
// AVX-512 hosts. A span's stores are blends of what it loaded: the columns from origin_x to the
// end of the tile of the rectangle's last column (and the row) are this worker's (row_spans'
// limit); a span reaching past them takes masked loads and stores.
constexpr int kNarrowSpans = 4;

template <DepthFormat F, CompareOp Op, int Spans>
RASTERCMP_AVX2 bool narrow_spans(const KernelJob& j, const KernelDepth& d, const TileTarget& t) {
  const SpanDepth s = span_depth(j, d);
  const int32_t limit = std::min(t.width, (j.rect.x1 | (kTileSize - 1)) + 1);  // columns below it are ours
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i owner = _mm256_set1_epi32(int32_t(j.owner));
  const int32_t x = j.origin_x, y1 = j.rect.y1;
  __m256i e[Spans][3], gy[3], in_rect[Spans], in_limit[Spans];
  __m256 inner[Spans];
  bool masked[Spans];
  for (int k = 0; k < Spans; ++k) {
    const __m256i column = _mm256_add_epi32(_mm256_set1_epi32(x + 8 * k), lane);
    for (int i = 0; i < 3; ++i)
      e[k][i] = _mm256_add_epi32(_mm256_set1_epi32(j.g_minus_1[i]),
                                 _mm256_mullo_epi32(_mm256_sub_epi32(column, _mm256_set1_epi32(x)),
                                                    _mm256_set1_epi32(j.gx[i])));
    in_rect[k] = _mm256_and_si256(_mm256_cmpgt_epi32(column, _mm256_set1_epi32(j.rect.x0 - 1)),
                                  _mm256_cmpgt_epi32(_mm256_set1_epi32(j.rect.x1 + 1), column));
    in_limit[k] = _mm256_cmpgt_epi32(_mm256_set1_epi32(limit), column);
    masked[k] = x + 8 * k + 8 > limit;
    inner[k] = mul_add8(s.dzdx, _mm256_cvtepi32_ps(column), s.a0, s.fma);  // exact: integers below 2^24
  }
  for (int i = 0; i < 3; ++i) gy[i] = _mm256_set1_epi32(j.gy[i]);
  const size_t width = size_t(t.width);
  uint32_t* owner_row = t.owner + size_t(j.rect.y0) * width + size_t(x);
  uint32_t* depth_row = F != DepthFormat::None ? t.depth + size_t(j.rect.y0) * width + size_t(x) : nullptr;
  __m256i any = _mm256_setzero_si256();
  for (int32_t y = j.rect.y0; y <= y1; ++y, owner_row += width) {
    const __m256 py = _mm256_set1_ps(float(y));
    for (int k = 0; k < Spans; ++k) {
      const __m256i out = _mm256_or_si256(_mm256_or_si256(e[k][0], e[k][1]), e[k][2]);
      __m256i pass = _mm256_andnot_si256(_mm256_srai_epi32(out, 31), in_rect[k]);
      if constexpr (F != DepthFormat::None) {
        const __m256 z = span_z_inner(s, inner[k], py);
        const __m256i raw = to_raw<F>(z);
        uint32_t* depth_span = depth_row + 8 * k;
        const __m256i stored = load_lanes(depth_span, in_limit[k], masked[k]);
        if constexpr (Op != CompareOp::Always) pass = _mm256_and_si256(pass, depth_passes<F, Op>(z, raw, stored));
        if (s.write) store_lanes(depth_span, raw, stored, pass, masked[k]);
      }
      uint32_t* owner_span = owner_row + 8 * k;
      store_lanes(owner_span, owner, load_lanes(owner_span, in_limit[k], masked[k]), pass, masked[k]);
      any = _mm256_or_si256(any, pass);
    }
    if constexpr (F != DepthFormat::None) depth_row += width;
    for (int k = 0; k < Spans; ++k)
      for (int i = 0; i < 3; ++i) e[k][i] = _mm256_add_epi32(e[k][i], gy[i]);
  }
  return !_mm256_testz_si256(any, any);
}

template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool kernel(const KernelJob& j, const KernelDepth& d, const TileTarget& t) {
  if constexpr (Op == CompareOp::Never && F != DepthFormat::None) return false;
  if (j.all_in && (j.rect.x0 & 7) == 0 && ((j.rect.x1 + 1) & 7) == 0) return covered_spans<F, Op>(j, d, t);
  switch ((j.rect.x1 - j.origin_x) >> 3) {
    case 0: return narrow_spans<F, Op, 1>(j, d, t);
    case 1: return narrow_spans<F, Op, 2>(j, d, t);
    case 2: return narrow_spans<F, Op, 3>(j, d, t);
    case 3: return narrow_spans<F, Op, 4>(j, d, t);
    default: break;
  }
  static_assert(kNarrowSpans == 4, "the cases above");
  return row_spans<F, Op>(j, d, t);
}

// ---- small triangles (small_triangles.hpp): one lane of a SmallBlockOutput, everything that
// does not change from row to row hoisted out of the loop (edge steps, the x mask, the inner FMA
// of the depth plane, which depends on px only).

// z of a group of lanes whose inner FMA?(dzdx, px, a0) is already known; then the depth test.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 inline __m256i small_depth(const KernelDepth& d, __m256 inner, __m256 py, __m256 dzdy, __m256i covered,
                                          __m256i stored, __m256i& raw) {
  // + o with o = 0 (draws with depth bias take the scalar set-up); the add turns -0 into +0
  const __m256 z = finish_depth8(mul_add8(dzdy, py, inner, d.fma), _mm256_setzero_ps(), d);
  raw = to_raw<F>(z);
  if constexpr (Op == CompareOp::Always)
    return covered;
  else
    return _mm256_and_si256(covered, depth_passes<F, Op>(z, raw, stored));
}

// A 4x2 group: row y in lanes 0-3, row y+1 in lanes 4-7 (when `two_rows`).
RASTERCMP_AVX2 inline __m256i load_4x2(const uint32_t* row0, const uint32_t* row1, bool two_rows) {
  const __m128i lo = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row0));
  const __m128i hi = two_rows ? _mm_loadu_si128(reinterpret_cast<const __m128i*>(row1)) : _mm_setzero_si128();
  return _mm256_inserti128_si256(_mm256_castsi128_si256(lo), hi, 1);
}

RASTERCMP_AVX2 inline void store_4x2(uint32_t* row0, uint32_t* row1, bool two_rows, __m256i value) {
  _mm_storeu_si128(reinterpret_cast<__m128i*>(row0), _mm256_castsi256_si128(value));
  if (two_rows) _mm_storeu_si128(reinterpret_cast<__m128i*>(row1), _mm256_extracti128_si256(value, 1));
}

// A triangle whose rectangle is at most 4 pixels wide, 4x2 pixels per step, in rows [row_lo, y1];
// the 4 columns from ox lie inside x1's tile and the framebuffer (small_kernel checks the latter).
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool small_4x2(const SmallBlockOutput& b, int l, int32_t ox, int32_t row_lo, int32_t y1,
                              uint32_t owner_id, const KernelDepth& d, const TileTarget& t) {
  const int32_t x0 = b.x0[l], x1 = b.x1[l];
  const __m256i lx = _mm256_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3), ly = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1);
  __m256i e[3], step[3];
  for (int i = 0; i < 3; ++i) {
    const __m256i gx = _mm256_set1_epi32(b.gx[i][l]), gy = _mm256_set1_epi32(b.gy[i][l]);
    e[i] = _mm256_add_epi32(_mm256_set1_epi32(b.edge_minus_1(l, i, ox, row_lo)),
                            _mm256_add_epi32(_mm256_mullo_epi32(lx, gx), _mm256_mullo_epi32(ly, gy)));
    step[i] = _mm256_slli_epi32(gy, 1);
  }
  const __m256i xv = _mm256_add_epi32(_mm256_set1_epi32(ox), lx);
  const __m256i in_x = _mm256_and_si256(_mm256_cmpgt_epi32(xv, _mm256_set1_epi32(x0 - 1)),
                                        _mm256_cmpgt_epi32(_mm256_set1_epi32(x1 + 1), xv));
  const __m256 a0 = _mm256_set1_ps(b.a0[l]), dzdx = _mm256_set1_ps(b.dzdx[l]), dzdy = _mm256_set1_ps(b.dzdy[l]);
  const __m256 px = _mm256_cvtepi32_ps(xv);
  const __m256 inner = mul_add8(dzdx, px, a0, d.fma);
  const __m256 lyf = _mm256_cvtepi32_ps(ly);
  const __m256i owner = _mm256_set1_epi32(int32_t(owner_id));
  const __m256i low_row = _mm256_setr_epi32(-1, -1, -1, -1, 0, 0, 0, 0);
  bool any = false;
  for (int32_t y = row_lo; y <= y1; y += 2) {
    const bool two_rows = y < y1;
    __m256i covered =
        _mm256_andnot_si256(_mm256_srai_epi32(_mm256_or_si256(_mm256_or_si256(e[0], e[1]), e[2]), 31), in_x);
    for (int i = 0; i < 3; ++i) e[i] = _mm256_add_epi32(e[i], step[i]);
    if (!two_rows) covered = _mm256_and_si256(covered, low_row);
    if (_mm256_testz_si256(covered, covered)) continue;
    const size_t row0 = size_t(y) * size_t(t.width) + size_t(ox), row1 = row0 + size_t(t.width);
    __m256i pass = covered;
    if constexpr (F != DepthFormat::None) {
      const __m256i stored = load_4x2(t.depth + row0, t.depth + row1, two_rows);
      __m256i raw;
      pass = small_depth<F, Op>(d, inner, _mm256_add_ps(_mm256_set1_ps(float(y)), lyf), dzdy, covered, stored, raw);
      if (_mm256_testz_si256(pass, pass)) continue;
      if (d.write) store_4x2(t.depth + row0, t.depth + row1, two_rows, _mm256_blendv_epi8(stored, raw, pass));
    }
    const __m256i old = load_4x2(t.owner + row0, t.owner + row1, two_rows);
    store_4x2(t.owner + row0, t.owner + row1, two_rows, _mm256_blendv_epi8(old, owner, pass));
    any = true;
  }
  return any;
}

template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX2 bool small_kernel(const SmallBlockOutput& b, int l, uint32_t owner, int32_t row_lo, int32_t row_hi,
                                 const KernelDepth& d, const TileTarget& t) {
  if constexpr (Op == CompareOp::Never && F != DepthFormat::None) return false;
  if (b.x1[l] - b.x0[l] < 4) {
    const int32_t ox = std::min(b.x0[l], (b.x1[l] | (kTileSize - 1)) - 3);
    if (ox + 4 <= t.width) return small_4x2<F, Op>(b, l, ox, row_lo, row_hi, owner, d, t);
  }
  return kernel<F, Op>(b.job(l, owner, Op, row_lo, row_hi), d, t);
}

struct SmallKernels {
  template <DepthFormat F, CompareOp Op>
  static constexpr SmallKernelFn get() {
    return &small_kernel<F, Op>;
  }
};
constexpr auto kSmallKernels = kernel_table<SmallKernels>();  // [format][op] (format_dispatch.hpp)

struct Kernels {
  template <DepthFormat F, CompareOp Op>
  static constexpr KernelFn get() {
    return &kernel<F, Op>;
  }
};
constexpr auto kKernels = kernel_table<Kernels>();

}  // namespace

KernelFn select_kernel_avx2(DepthFormat format, CompareOp op) { return select_kernel(kKernels, format, op); }

RASTERCMP_AVX2 void covered_columns_avx2(const KernelJob& j, int32_t* x0, int32_t* x1) {
  for (int32_t y = j.rect.y0; y <= j.rect.y1; ++y) x0[y - j.rect.y0] = 1, x1[y - j.rect.y0] = 0;
  CoveredRows rows;
  init_covered_rows(rows, j);
  int32_t y, first, last;
  while (rows.next(y, first, last)) x0[y - j.rect.y0] = first, x1[y - j.rect.y0] = last;
}

SmallKernelFn select_small_kernel_avx2(DepthFormat format, CompareOp op) {
  return select_kernel(kSmallKernels, format, op);
}

RASTERCMP_AVX2 void measure_bounds_avx2(const uint32_t* depth, int32_t width, const PixelRect& r, uint32_t& lo,
                                        uint32_t& hi) {
  __m256i vlo = _mm256_set1_epi32(-1), vhi = _mm256_setzero_si256();
  uint32_t slo = UINT32_MAX, shi = 0;
  for (int32_t y = r.y0; y <= r.y1; ++y) {
    const uint32_t* row = depth + size_t(y) * size_t(width);
    int32_t x = r.x0;
    for (; x + 8 <= r.x1 + 1; x += 8) {
      const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row + x));
      vlo = _mm256_min_epu32(vlo, v);
      vhi = _mm256_max_epu32(vhi, v);
    }
    for (; x <= r.x1; ++x) {
      slo = row[x] < slo ? row[x] : slo;
      shi = row[x] > shi ? row[x] : shi;
    }
  }
  alignas(32) uint32_t lanes_lo[8], lanes_hi[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(lanes_lo), vlo);
  _mm256_store_si256(reinterpret_cast<__m256i*>(lanes_hi), vhi);
  for (int i = 0; i < 8; ++i) {
    slo = lanes_lo[i] < slo ? lanes_lo[i] : slo;
    shi = lanes_hi[i] > shi ? lanes_hi[i] : shi;
  }
  lo = slo;
  hi = shi;
}

// No streaming stores: those f1351bf used for runs of 256 KiB and more were slower once tile
// rows were cleared whole (clear_tile_row: the rows a draw goes on to write were sent to memory;
// docs/performance-log.md, 96b2e7d). Runs of kRepStosWords and more (whole rows of tiles) take
// `rep stosl` (ERMS/FSRM microcode): as fast as the vector stores when the lines are cached, and
// 10-25% faster when they are not, the usual case in a render that follows other work (a throw-away
// driver on 8 MiB after an eviction: 173 against 208-228 us; perspective after a lavapipe render
// -1 to -6%; docs/performance-log.md, d5199fc). Below it the vector stores (its start-up costs more).
constexpr size_t kRepStosWords = 4096;

RASTERCMP_AVX2 void fill_words_avx2(uint32_t* p, size_t count, uint32_t value) {
  if (count >= kRepStosWords) {
    asm volatile("rep stosl" : "+D"(p), "+c"(count) : "a"(value) : "memory");
    return;
  }
  const __m256i v = _mm256_set1_epi32(int(value));
  size_t i = 0;
  for (; i + 32 <= count; i += 32) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p + i), v);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p + i + 8), v);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p + i + 16), v);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p + i + 24), v);
  }
  for (; i + 8 <= count; i += 8) _mm256_storeu_si256(reinterpret_cast<__m256i*>(p + i), v);
  for (; i < count; ++i) p[i] = value;
}

// The raw depths of a row of samples for the exact rows (exact_rows.cpp): lane k is column x0 + k,
// x = float(x0 + k) + sx as sample_point forms it, then sample_depth's operations one intrinsic each
// (span_z, to_raw).
template <DepthFormat F>
RASTERCMP_AVX2 void sample_depths(const SampleRowDepth& row, const KernelDepth& d, int32_t x0, int32_t count,
                                  uint32_t* raw) {
  const __m256 a0 = _mm256_set1_ps(row.a0), dzdx = _mm256_set1_ps(row.dzdx), dzdy = _mm256_set1_ps(row.dzdy);
  const __m256 offset = _mm256_set1_ps(row.offset), sx = _mm256_set1_ps(row.sx), y = _mm256_set1_ps(row.y);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (int32_t k = 0; k < count; k += 8) {
    const __m256 x = _mm256_add_ps(_mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(x0 + k), lane)), sx);
    const __m256 z = finish_depth8(mul_add8(dzdy, y, mul_add8(dzdx, x, a0, d.fma), d.fma), offset, d);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(raw + k), to_raw<F>(z));
  }
}

RASTERCMP_AVX2 void sample_depths_avx2(const SampleRowDepth& row, const KernelDepth& d, int32_t x0, int32_t count,
                                       uint32_t* raw) {
  if (d.format == DepthFormat::None) return;
  with_depth_format(d.format, [&]<DepthFormat F>() RASTERCMP_AVX2 {
    if constexpr (F != DepthFormat::None) sample_depths<F>(row, d, x0, count, raw);
  });
}

}  // namespace rastercmp::cpu::fast
