#include "cpu_raster/fast/exact_rows.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <optional>

#include "cpu_raster/fast/binned_tiles.hpp"
#include "cpu_raster/fast/tile_kernel.hpp"

namespace rastercmp::cpu::fast {
namespace {

int64_t floor_div(int64_t a, int64_t d) {  // d > 0
  const int64_t q = a / d;
  return (a % d != 0 && a < 0) ? q - 1 : q;
}

}  // namespace

bool plane_columns(const EdgePlane& plane, int64_t sample_x, int64_t y_fixed, int32_t& x0, int32_t& x1) {
  const int64_t k = edge_value(plane, sample_x, y_fixed);  // E at column 0; E(px) = k - dcdx * kFixedOne * px
  if (plane.dcdx == 0) return k > 0 && x0 <= x1;
  if (plane.dcdx > 0) {  // k - d px > 0  <=>  px <= floor((k - 1) / d)
    const int64_t last = floor_div(k - 1, plane.dcdx * kFixedOne);
    x1 = int32_t(std::min<int64_t>(x1, last));
  } else {  // k + d px > 0  <=>  px >= floor(-k / d) + 1
    const int64_t first = floor_div(-k, -plane.dcdx * kFixedOne) + 1;
    x0 = int32_t(std::max<int64_t>(x0, first));
  }
  return x0 <= x1;
}

namespace {

// The owner writes of a covered (column, sample) that passed (rasterize_primitive's loop body).
void write_owner(const RasterPrimitive& p, RenderTargets& targets, int32_t px, int32_t py, size_t i) {
  if (p.per_sample) {
    targets.owner[i] = p.owner;
  } else {
    for (uint32_t t = 0; t < targets.samples; ++t) targets.owner[targets.index(px, py, t)] = p.owner;
  }
}

// The writes of one covered (column, sample) of a primitive (rasterize_primitive's loop body): with
// an active depth test only evaluate_sample's depth work is left to do.
void write_covered_sample(const RasterPrimitive& p, const DepthTestState& depth, RenderTargets& targets, int32_t px,
                          int32_t py, uint32_t s, const EdgeFrame32* edges32) {
  const bool read_stored = (depth.active || depth.compute_when_inactive) && !targets.depth_raw.empty();
  const size_t i = targets.index(px, py, s);
  if (depth.active && !depth.compute_when_inactive) {
    const SamplePoint point = sample_point(px, py, s, p.per_sample);
    const SampleDepth z = sample_depth(p.depth, p.offset.offset, point.x, point.y, depth.range, depth.format, depth.fma);
    if (!depth_test_passes(depth.op, depth.format, z.raw, read_stored ? targets.depth_raw[i] : 0)) return;
    if (depth.write) targets.depth_raw[i] = z.raw;
  } else {
    const SampleVerdict verdict = evaluate_sample(p, depth, px, py, s, read_stored ? targets.depth_raw[i] : 0, edges32);
    if (!verdict.passes()) return;
    if (depth.write) targets.depth_raw[i] = verdict.depth.raw;
  }
  write_owner(p, targets, px, py, i);
}

// Whether the covered samples of a row may go to write_covered_row_avx2 (on an AVX2 host): the
// branch of write_covered_sample that computes only the depth, with an attachment.
bool depth_rows_avx2(const DepthTestState& depth, const RenderTargets& targets) {
  return depth.active && !depth.compute_when_inactive && depth.format != DepthFormat::None &&
         !targets.depth_raw.empty();
}

// Columns [x0, x1] of one sample row, all covered, with an active depth test (the branch of
// write_covered_sample that computes only the depth): the raw depths eight columns at a time
// (sample_depths_avx2, the same operations as sample_point and sample_depth), then the test and
// the writes column by column as write_covered_sample does them.
void write_covered_row_avx2(const RasterPrimitive& p, const DepthTestState& depth, RenderTargets& targets, int32_t py,
                            uint32_t s, const SamplePoint& origin, int32_t x0, int32_t x1) {
  constexpr int32_t kChunk = 64;
  const KernelDepth kernel_depth{depth.format, depth.op,        depth.write,     depth.range.clamp,
                                 depth.range.zmin, depth.range.zmax, depth.fma};
  const SampleRowDepth row{p.depth.a0, p.depth.dzdx, p.depth.dzdy, p.offset.offset, origin.x, origin.y};
  alignas(32) uint32_t raw[kChunk];
  for (int32_t cx = x0; cx <= x1; cx += kChunk) {
    const int32_t count = std::min(kChunk, x1 - cx + 1);
    sample_depths_avx2(row, kernel_depth, cx, count, raw);
    for (int32_t k = 0; k < count; ++k) {
      const int32_t px = cx + k;
      const size_t i = targets.index(px, py, s);
      if (!depth_test_passes(depth.op, depth.format, raw[k], targets.depth_raw[i])) continue;
      if (depth.write) targets.depth_raw[i] = raw[k];
      write_owner(p, targets, px, py, i);
    }
  }
}

}  // namespace

// rasterize_primitive (rasterize.cpp) with the loops over a row's columns and its samples swapped
// (every (column, sample) of a primitive writes its own values: the order between them does not
// matter) and each sample's columns cut to plane_columns of every plane.
void rasterize_primitive_rows(const RasterPrimitive& p, const DepthTestState& depth, RenderTargets& targets,
                              bool avx2) {
  const std::optional<EdgeFrame32> frame32 = make_edge_frame32(p.planes, p.visit);  // as WorkSkips{} does
  const EdgeFrame32* edges32 = frame32 ? &*frame32 : nullptr;
  const uint32_t tested_samples = p.per_sample ? targets.samples : 1;
  const bool rows_avx2 = avx2 && depth_rows_avx2(depth, targets);
  for (int32_t py = p.visit.y0; py <= p.visit.y1; ++py) {
    for (uint32_t s = 0; s < tested_samples; ++s) {
      const SamplePoint origin = sample_point(0, py, s, p.per_sample);
      int32_t x0 = p.visit.x0, x1 = p.visit.x1;
      bool any = true;
      for (uint32_t i = 0; i < p.planes.count && any; ++i)
        any = plane_columns(p.planes.plane[i], origin.x_fixed, origin.y_fixed, x0, x1);
      if (!any) continue;
      if (rows_avx2) {
        write_covered_row_avx2(p, depth, targets, py, s, origin, x0, x1);
        continue;
      }
      for (int32_t px = x0; px <= x1; ++px) write_covered_sample(p, depth, targets, px, py, s, edges32);
    }
  }
}

// rasterize_primitive for a binned primitive (llvmpipe's wrapping set-up, binned_triangle.hpp), the
// same loops swapped, with coverage a 64x64 tile at a time (binned_tile_coverage: what binned_covers
// answers for each of its pixels); with avx2, each run of covered columns goes to
// write_covered_row_avx2 (the same writes as write_covered_sample's depth branch, column by column).
void rasterize_binned_rows(const RasterPrimitive& p, const DepthTestState& depth, RenderTargets& targets, bool avx2) {
  const BinnedTriangle& t = *p.binned;
  const uint32_t tested_samples = p.per_sample ? targets.samples : 1;
  const bool rows_avx2 = avx2 && depth_rows_avx2(depth, targets);
  const PixelRect visit = intersect(p.visit, PixelRect{0, 0, t.tiles_x * kBinTile - 1, t.tiles_y * kBinTile - 1});
  if (visit.empty()) return;  // binned_covers is false outside the tiles
  std::array<uint64_t, kBinTile> rows;
  for (int32_t ty = visit.y0 / kBinTile; ty <= visit.y1 / kBinTile; ++ty) {
    const int32_t y0 = std::max(visit.y0, ty * kBinTile), y1 = std::min(visit.y1, ty * kBinTile + kBinTile - 1);
    for (int32_t tx = visit.x0 / kBinTile; tx <= visit.x1 / kBinTile; ++tx) {
      if (t.tile_planes[size_t(ty) * size_t(t.tiles_x) + size_t(tx)] == 0) continue;  // not binned: none covered
      const int32_t x0 = std::max(visit.x0, tx * kBinTile), x1 = std::min(visit.x1, tx * kBinTile + kBinTile - 1);
      const uint64_t columns = (~uint64_t(0) >> (63 - (x1 - tx * kBinTile))) & (~uint64_t(0) << (x0 - tx * kBinTile));
      for (uint32_t s = 0; s < tested_samples; ++s) {
        binned_tile_coverage(t, tx, ty, p.per_sample ? s : 0, rows);
        for (int32_t py = y0; py <= y1; ++py) {
          uint64_t bits = rows[size_t(py - ty * kBinTile)] & columns;
          if (rows_avx2 && bits != 0) {  // a run of covered columns at a time (a triangle's row: one)
            const SamplePoint origin = sample_point(0, py, s, p.per_sample);
            for (; bits != 0; bits &= bits + (bits & (~bits + 1))) {  // the lowest run cleared
              const int32_t first = std::countr_zero(bits), length = std::countr_one(bits >> first);
              write_covered_row_avx2(p, depth, targets, py, s, origin, tx * kBinTile + first,
                                     tx * kBinTile + first + length - 1);
            }
            continue;
          }
          for (; bits != 0; bits &= bits - 1)
            write_covered_sample(p, depth, targets, tx * kBinTile + std::countr_zero(bits), py, s, nullptr);
        }
      }
    }
  }
}

}  // namespace rastercmp::cpu::fast
