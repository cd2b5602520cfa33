// The 4x box kernel of exact_rows_4x_avx2.cpp (sample_box_rows) sixteen lanes wide, for AVX-512
// hosts: four pixels' four samples per step, one 64-byte line of each attachment (a step starts
// on a pixel whose index is a multiple of four, and both attachments start on a page boundary or
// half a page after one). Lane l is sample l % 4 of pixel px + l / 4.
//
// Coverage. n = E - 1 of plane i at lane (column px, sample s) of row py is c + (dcdy * sy[s] -
// dcdx * sx[s]) + (px - start) * gx + (py - y0) * gy, with c its value at the corner of pixel
// (start, y0), start = x0 - 3, gx = -dcdx * 256, gy = dcdy * 256 and the sample offsets sx, sy in
// (0, 256): an integer, covered iff n >= 0 for every plane, so iff the OR of the planes' n has its
// sign bit clear. A row's steps run from x0 - ((py * width + x0) mod 4), at least start, to at most
// x1 + 3, so every value a step forms is bounded by |c| + |gx| * (x1 + 4 - start) + |gy| * (y1 - y0
// + 1), checked below 2^31 in int64 per plane (the column step past a row's last and the row step
// past y1 may wrap; they are never read). Lanes outside [x0, x1] are masked off: the exact path
// visits only those columns, and a masked lane is neither read nor written (AVX-512 masked loads
// and stores do not fault on masked-off lanes, so a step may start before the row or end past it).
//
// Depth: sample_point's floats (float(px) + the sample's x offset, float(py) + its y offset), z =
// fl(FMA?(dzdy, y, FMA?(dzdx, x, a0)) + o), min 1, max 0 and the clamp, the raw value and the test
// (avx512_depth.hpp: avx2_depth.hpp's operations on sixteen lanes), then masked writes of the
// passing lanes. A step holds distinct samples of one primitive, so reading its stored values
// before writing any reads what the exact path's sample by sample order reads.
#include "cpu_raster/fast/avx512_depth.hpp"
#include "cpu_raster/fast/exact_rows.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"

namespace rastercmp::cpu::fast {
namespace {

template <DepthFormat F, CompareOp Op, uint32_t Planes>
RASTERCMP_AVX512 bool box16(const RasterPrimitive& p, int32_t y0, int32_t y1, const KernelDepth& kd,
                            RenderTargets& targets) {
  constexpr int Samples = 4;
  const int32_t x0 = p.visit.x0, x1 = p.visit.x1, width = int32_t(targets.width);
  const uint32_t planes = Planes != 0 ? Planes : p.planes.count;
  const int32_t start = x0 - 3;
  const int64_t reach_x = int64_t(x1) + 4 - start, reach_y = int64_t(y1) - y0 + 1;
  // lane l: pixel l / 4, sample l % 4 (its fixed and float offsets), constants
  static constexpr auto kLanes = [] {
    struct {
      alignas(64) int32_t pixel[16], x_fixed[16], y_fixed[16];
      alignas(64) float x[16], y[16];
    } lanes{};
    for (int l = 0; l < 16; ++l) {
      lanes.pixel[l] = l / Samples;
      lanes.x_fixed[l] = kStandardSamples4x[l % Samples].x_fixed;
      lanes.y_fixed[l] = kStandardSamples4x[l % Samples].y_fixed;
      lanes.x[l] = kStandardSamples4x[l % Samples].x;
      lanes.y[l] = kStandardSamples4x[l % Samples].y;
    }
    return lanes;
  }();
  const __m512i lane_pixel = _mm512_load_si512(kLanes.pixel), lane_x = _mm512_load_si512(kLanes.x_fixed),
                lane_y = _mm512_load_si512(kLanes.y_fixed);
  const __m512 sx = _mm512_load_ps(kLanes.x), sy = _mm512_load_ps(kLanes.y);
  __m512i row_n[8], gx1[8], gx4[8], gy[8];
  for (uint32_t i = 0; i < planes; ++i) {
    const EdgePlane& plane = p.planes.plane[i];
    BoxPlane b;
    if (!box_plane(plane, start, y0, reach_x, reach_y, b)) return false;
    const __m512i offsets = _mm512_sub_epi32(_mm512_mullo_epi32(_mm512_set1_epi32(int32_t(plane.dcdy)), lane_y),
                                             _mm512_mullo_epi32(_mm512_set1_epi32(int32_t(plane.dcdx)), lane_x));
    gx1[i] = _mm512_set1_epi32(int32_t(b.gx));
    row_n[i] = _mm512_add_epi32(_mm512_add_epi32(_mm512_set1_epi32(int32_t(b.corner)), offsets),
                                _mm512_mullo_epi32(gx1[i], lane_pixel));
    gx4[i] = _mm512_set1_epi32(int32_t(4 * b.gx));
    gy[i] = _mm512_set1_epi32(int32_t(b.gy));
  }
  uint32_t* depth = targets.depth_raw.data();
  uint32_t* owner = targets.owner.data();
  const Depth16 d = depth16(kd);
  const __m512 a0 = _mm512_set1_ps(p.depth.a0), dzdx = _mm512_set1_ps(p.depth.dzdx),
               dzdy = _mm512_set1_ps(p.depth.dzdy);
  const __m512 offset = _mm512_set1_ps(p.offset.offset);
  const __m512i id = _mm512_set1_epi32(int32_t(p.owner));
  const __m512i first_column = _mm512_set1_epi32(x0), last_column = _mm512_set1_epi32(x1);
  for (int32_t py = y0; py <= y1; ++py) {
    const int32_t lead = int32_t((size_t(py) * size_t(width) + size_t(x0)) & 3u);  // first = start + 3 - lead
    __m512i n[8];
    for (uint32_t i = 0; i < planes; ++i) {
      n[i] = _mm512_add_epi32(row_n[i], _mm512_mullo_epi32(gx1[i], _mm512_set1_epi32(3 - lead)));
      row_n[i] = _mm512_add_epi32(row_n[i], gy[i]);
    }
    const __m512 y = _mm512_add_ps(_mm512_set1_ps(float(py)), sy);
    uint32_t* depth_row = depth + size_t(py) * size_t(width) * Samples;
    uint32_t* owner_row = owner + size_t(py) * size_t(width) * Samples;
    for (int32_t px = x0 - lead; px <= x1; px += 4) {
      __m512i any_out = n[0];
      n[0] = _mm512_add_epi32(n[0], gx4[0]);
      for (uint32_t i = 1; i < planes; ++i) {
        any_out = _mm512_or_si512(any_out, n[i]);
        n[i] = _mm512_add_epi32(n[i], gx4[i]);
      }
      const __mmask16 inside_planes = _mm512_movepi32_mask(any_out) ^ __mmask16(0xFFFF);
      if (inside_planes == 0) continue;
      const __m512i pixel = _mm512_add_epi32(_mm512_set1_epi32(px), lane_pixel);
      const __mmask16 covered = _mm512_mask_cmple_epi32_mask(
          _mm512_mask_cmpge_epi32_mask(inside_planes, pixel, first_column), pixel, last_column);
      if (covered == 0) continue;
      const __m512 x = _mm512_add_ps(_mm512_cvtepi32_ps(pixel), sx);
      const __m512 z =
          finish_depth16(_mm512_add_ps(mul_add16(dzdy, y, mul_add16(dzdx, x, a0, d.fma), d.fma), offset), d);
      const __m512i raw = to_raw16<F>(z);
      uint32_t* dp = depth_row + ptrdiff_t(px) * Samples;
      const __mmask16 pass = passing<F, Op>(covered, raw, _mm512_maskz_loadu_epi32(covered, dp));
      if (pass == 0) continue;
      if (d.write) _mm512_mask_storeu_epi32(dp, pass, raw);
      _mm512_mask_storeu_epi32(owner_row + ptrdiff_t(px) * Samples, pass, id);
    }
  }
  return true;
}

template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 bool box_kernel(const RasterPrimitive& p, int32_t y0, int32_t y1, const KernelDepth& d,
                                 RenderTargets& targets) {
  return p.planes.count == 3 ? box16<F, Op, 3>(p, y0, y1, d, targets) : box16<F, Op, 0>(p, y0, y1, d, targets);
}

using BoxFn = bool (*)(const RasterPrimitive&, int32_t, int32_t, const KernelDepth&, RenderTargets&);

struct BoxMaker {
  template <DepthFormat F, CompareOp Op>
  static constexpr BoxFn get() {
    if constexpr (F == DepthFormat::None || Op == CompareOp::Never)
      return nullptr;
    else
      return &box_kernel<F, Op>;
  }
};
constexpr auto kBoxes = kernel_table<BoxMaker>();

}  // namespace

bool rasterize_box_avx512(const RasterPrimitive& p, int32_t y0, int32_t y1, const DepthTestState& depth,
                          RenderTargets& targets) {
  if (p.binned || depth.compute_when_inactive || !p.per_sample || targets.samples != 4 || !depth.active ||
      depth.format == DepthFormat::None || targets.depth_raw.empty() || depth.op == CompareOp::Never)
    return false;
  if (y0 > y1 || p.visit.x0 > p.visit.x1) return false;
  const int32_t columns = p.visit.x1 - p.visit.x0 + 1;
  if (columns > kBoxColumns || columns * (y1 - y0 + 1) > kBoxPixels) return false;
  const KernelDepth d{depth.format,     depth.op,         depth.write, depth.range.clamp,
                      depth.range.zmin, depth.range.zmax, depth.fma};
  return select_kernel(kBoxes, depth.format, depth.op)(p, y0, y1, d, targets);
}

}  // namespace rastercmp::cpu::fast
