// The tile kernel (tile_kernel.hpp) on AVX-512 hosts: each row's covered columns from the edges
// (row_columns_avx2.hpp, the same code as the AVX2 kernel's), then sixteen pixels per step, the
// columns past the row's last covered one masked off. A step has no branch on its data: the masked
// loads and stores touch only covered pixels (so never a pixel outside the rectangle, which lies
// inside one tile and the framebuffer), and the depth test is a mask. The depth arithmetic is
// avx512_depth.hpp's, avx2_depth.hpp's operations one intrinsic each on sixteen lanes.
#include <immintrin.h>

// GCC 12's own AVX-512 headers pass _mm512_undefined_ps() as the merge source of vminps and
// friends, which -Wuninitialized reports at every use once inlined (a false positive: unmasked).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "cpu_raster/fast/avx512_depth.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/format_dispatch.hpp"
#include "cpu_raster/fast/row_columns_avx2.hpp"
#include "cpu_raster/fast/small_triangles.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"

namespace rastercmp::cpu::fast {
namespace {

// The job's plane and the draw's depth state in registers (stores to the attachments may alias
// the job and the KernelDepth, so their fields would be reloaded after each store otherwise).
struct Plane16 {
  __m512 a0, dzdx, dzdy, offset, zmin, zmax;
  bool fma, clamp, write;
};

RASTERCMP_AVX512 inline Plane16 plane16(const KernelJob& j, const KernelDepth& d) {
  return Plane16{_mm512_set1_ps(j.a0),     _mm512_set1_ps(j.dzdx), _mm512_set1_ps(j.dzdy),
                 _mm512_set1_ps(j.offset), _mm512_set1_ps(d.zmin), _mm512_set1_ps(d.zmax),
                 d.fma,                    d.clamp,                d.write};
}

// fragment_depth (tile_kernel_avx2.cpp) in the same order: fl(FMA?(dzdy, py, FMA?(dzdx, px, a0)) + o),
// min(z, 1), max(z, 0), then the depth clamp.
RASTERCMP_AVX512 inline __m512 depth16(const Plane16& p, __m512 px, __m512 py) {
  __m512 z = _mm512_add_ps(mul_add16(p.dzdy, py, mul_add16(p.dzdx, px, p.a0, p.fma), p.fma), p.offset);
  z = _mm512_max_ps(_mm512_min_ps(z, _mm512_set1_ps(1.0f)), _mm512_setzero_ps());
  if (p.clamp) z = _mm512_max_ps(_mm512_min_ps(z, p.zmax), p.zmin);
  return z;
}

template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 bool kernel16(const KernelJob& j, const KernelDepth& d, const TileTarget& t) {
  if constexpr (Op == CompareOp::Never && F != DepthFormat::None) return false;
  const Plane16 plane = plane16(j, d);
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i owner = _mm512_set1_epi32(int32_t(j.owner));
  const size_t width = size_t(t.width);
  __mmask16 any = 0;
  CoveredRows rows;
  init_covered_rows(rows, j);
  int32_t y, x, x_end;
  while (rows.next(y, x, x_end)) {
    const __m512 py = _mm512_set1_ps(float(y));
    uint32_t* const owner_row = t.owner + size_t(y) * width;
    uint32_t* const depth_row = F != DepthFormat::None ? t.depth + size_t(y) * width : nullptr;
    for (; x <= x_end; x += 16) {
      const uint32_t left = uint32_t(x_end - x + 1);
      const __mmask16 columns = __mmask16(left >= 16 ? 0xFFFFu : (1u << left) - 1u);
      __mmask16 pass = columns;
      if constexpr (F != DepthFormat::None) {
        const __m512 px = _mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(x), lane));  // exact below 2^24
        const __m512i raw = to_raw16<F>(depth16(plane, px, py));
        if constexpr (Op != CompareOp::Always)
          pass = passing<F, Op>(columns, raw, _mm512_maskz_loadu_epi32(columns, depth_row + x));
        if (plane.write) _mm512_mask_storeu_epi32(depth_row + x, pass, raw);
      }
      _mm512_mask_storeu_epi32(owner_row + x, pass, owner);
      any |= pass;
    }
  }
  return any != 0;
}

// A kernel job of a small-triangle block (small_triangles.hpp): the same kernel on the lane's job.
template <DepthFormat F, CompareOp Op>
RASTERCMP_AVX512 bool small_kernel16(const SmallBlockOutput& b, int lane, uint32_t owner, const KernelDepth& d,
                                     const TileTarget& t) {
  return kernel16<F, Op>(b.job(lane, owner, Op), d, t);
}

struct SmallKernels {
  template <DepthFormat F, CompareOp Op>
  static constexpr SmallKernelFn get() {
    return &small_kernel16<F, Op>;
  }
};
constexpr auto kSmallKernels = kernel_table<SmallKernels>();

struct Kernels {
  template <DepthFormat F, CompareOp Op>
  static constexpr KernelFn get() {
    return &kernel16<F, Op>;
  }
};
constexpr auto kKernels = kernel_table<Kernels>();  // [format][op] (format_dispatch.hpp)

}  // namespace

KernelFn select_kernel_avx512(DepthFormat format, CompareOp op) { return select_kernel(kKernels, format, op); }

SmallKernelFn select_small_kernel_avx512(DepthFormat format, CompareOp op) {
  return select_kernel(kSmallKernels, format, op);
}

}  // namespace rastercmp::cpu::fast
