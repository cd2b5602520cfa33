#include "cpu_raster/fast/tile_raster.hpp"

#include <algorithm>

#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/fast/tile_edges.hpp"
#include "model/depth_format.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu::fast {
namespace {

// Below these areas the bounds cost more than they save (docs/performance.md).
constexpr int64_t kBoundsMinArea = 256;    // classify a triangle against the tile's bounds
constexpr int64_t kMeasureMinArea = 2048;  // re-measure a tile whose bounds are not exact

int64_t area(const PixelRect& r) { return int64_t(r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1); }

// The tile's bounds after the triangle wrote depth over r (`ranged`: the tile's bounds were
// known and the fragments' range is f).
void update_bounds(TileBounds& tile, bool ranged, const FragmentRange& f, DepthVerdict verdict, bool covers_tile) {
  if (!ranged) {
    tile.state = BoundsState::Unknown;
  } else if (verdict == DepthVerdict::AllPass && covers_tile) {
    tile = TileBounds{f.lo, f.hi, BoundsState::Exact};  // every stored value was replaced
  } else {
    tile = TileBounds{std::min(tile.zmin, f.lo), std::max(tile.zmax, f.hi), BoundsState::Loose};
  }
}

}  // namespace

DrawRaster make_draw_raster(const DepthTestState& depth, bool frame_bounds, bool avx2, bool avx512) {
  DrawRaster draw;
  draw.depth = depth;
  draw.kernel = KernelDepth{depth.active ? depth.format : DepthFormat::None,
                            depth.op,
                            depth.write,
                            depth.range.clamp,
                            depth.range.zmin,
                            depth.range.zmax,
                            depth.fma};
  const bool unorm = is_unorm(depth.format);
  draw.vector_ok = !(depth.active && unorm && depth.range.clamp && !(depth.range.zmin >= 0.0f));
  draw.bounds = frame_bounds && depth.active && depth_values_ordered(depth);
  if (avx2) {
    draw.small_fn = avx512 ? select_small_kernel_avx512(draw.kernel.format, depth.op)
                           : select_small_kernel_avx2(draw.kernel.format, depth.op);
    if (avx512) draw.small_piece_fn = select_small_piece_avx512(draw.kernel.format, depth.op);
    draw.grid_fn = select_grid_scatter(draw.kernel.format, depth.op);
    draw.grid_block_fn = select_grid_block(draw.kernel.format, depth.op);
    draw.window_block_fn = avx512 ? select_window_block_avx512(draw.kernel.format, depth.op)
                                  : select_window_block_avx2(draw.kernel.format, depth.op);
  }
  return draw;
}

TileTriangle prepare_in_tile(const FastTriangle& t, const PixelRect& r, const DrawRaster& draw, bool range_small) {
  TileTriangle p;
  p.edges = setup_tile_edges(t, r, p.job);
  if (p.edges.fit == EdgeFit::None) return p;
  p.ranged = draw.bounds && (range_small || area(r) >= kBoundsMinArea) && fragment_range(t, r, draw.depth, p.fragment);
  return p;
}

BoundsUse raster_in_tile(const FastTriangle& t, const PixelRect& r, int32_t tile_x, int32_t tile_y,
                         const DrawRaster& draw, const FrameRaster& frame) {
  return raster_prepared(t, prepare_in_tile(t, r, draw, false), tile_x, tile_y, draw, frame);
}

BoundsUse raster_prepared(const FastTriangle& t, const TileTriangle& prepared, int32_t tile_x, int32_t tile_y,
                          const DrawRaster& draw, const FrameRaster& frame) {
  const EdgeSetup& edges = prepared.edges;
  if (edges.fit == EdgeFit::None) return BoundsUse::None;
  KernelJob job = prepared.job;
  const PixelRect& r = job.rect;
  job.a0 = t.a0;
  job.dzdx = t.dzdx;
  job.dzdy = t.dzdy;
  job.offset = t.offset;
  job.owner = t.owner;
  job.op = draw.depth.op;
  job.all_in = edges.all_in;
  TileState& state = frame.tile(tile_x, tile_y);
  TileBounds& tile = state.bounds;
  const PixelRect whole_tile = tile_rect(tile_x, tile_y, frame.target);
  const FragmentRange& fragment = prepared.fragment;
  bool ranged = false, consulted = false;
  DepthVerdict verdict = DepthVerdict::PerPixel;
  if (draw.bounds && area(r) >= kBoundsMinArea && prepared.ranged) {
    consulted = true;
    const bool whole = r == whole_tile, measurable = area(r) >= kMeasureMinArea && state.cleared;
    if (tile.state != BoundsState::Exact && whole && measurable)
      measure_bounds(frame.target.depth, frame.target.width, whole_tile, frame.avx2, tile);
    if (tile.state != BoundsState::Unknown) {
      ranged = true;
      verdict = classify_depth(draw.depth.op, fragment, tile);
    }
    if (verdict == DepthVerdict::PerPixel && !whole && measurable) {  // the values under r alone
      TileBounds under;
      measure_bounds(frame.target.depth, frame.target.width, r, frame.avx2, under);
      const DepthVerdict local = classify_depth(draw.depth.op, fragment, under);
      if (local != DepthVerdict::PerPixel) verdict = local;
    }
    if (verdict == DepthVerdict::AllFail) return BoundsUse::Helped;

    if (verdict == DepthVerdict::AllPass) job.op = CompareOp::Always;
  }
  const bool covers_tile = prepared.covers(whole_tile);
  if (!state.cleared) {
    // Fast clear: skipped when this triangle replaces every owner and depth value of the tile.
    const bool overwrites =
        covers_tile && (frame.target.depth == nullptr || (draw.depth.write && verdict == DepthVerdict::AllPass));
    if (!overwrites) clear_tile_row(tile_y, state.worker, frame);
    state.cleared = true;
  }
  bool wrote;
  if (frame.avx2 && draw.vector_ok && edges.fit == EdgeFit::Vector) {
    const KernelFn kernel = frame.avx512 ? select_kernel_avx512(draw.kernel.format, job.op)
                                         : select_kernel_avx2(draw.kernel.format, job.op);
    wrote = kernel(job, draw.kernel, frame.target);
  } else {
    DepthTestState depth = draw.depth;
    depth.op = job.op;  // Always when the bounds proved every sample passes (and the tile may hold no clear values yet)
    wrote = raster_scalar(t, r, depth, frame.target);
  }
  // frame.bounds, not draw.bounds: a draw whose audit turned the bounds off still leaves the
  // tiles it writes with unknown bounds (BandWorker::BoundsAudit)
  if (wrote && draw.depth.write && frame.bounds) update_bounds(tile, ranged, fragment, verdict, covers_tile);
  if (!consulted) return BoundsUse::None;
  return verdict == DepthVerdict::PerPixel ? BoundsUse::PerPixel : BoundsUse::Helped;
}

// A run of neighbouring tiles is filled one pixel row at a time (the whole run at once where it
// spans the width): long runs of stores, which the hardware prefetcher keeps ahead of. Tile by
// tile, in the order a draw reaches them, the same 8 MiB took 0.23-0.27 ms instead of 0.09-0.10
// (docs/performance-log.md, 96b2e7d).
void clear_tile_row(int32_t tile_y, uint32_t worker, const FrameRaster& frame) {
  const auto to_clear = [&](int32_t tx) {
    const TileState& tile = frame.tile(tx, tile_y);
    return !tile.cleared && tile.worker == worker;
  };
  for (int32_t tx = 0; tx < frame.tiles_x; ++tx) {
    if (!to_clear(tx)) continue;
    int32_t last = tx;
    while (last + 1 < frame.tiles_x && to_clear(last + 1)) ++last;
    const PixelRect first_tile = tile_rect(tx, tile_y, frame.target), last_tile = tile_rect(last, tile_y, frame.target);
    clear_rect(PixelRect{first_tile.x0, first_tile.y0, last_tile.x1, last_tile.y1}, frame);
    for (int32_t k = tx; k <= last; ++k) frame.tile(k, tile_y).cleared = true;
    tx = last;
  }
}

namespace {
void fill_words(uint32_t* p, size_t count, uint32_t value, bool avx2) {
  if (avx2)
    fill_words_avx2(p, count, value);
  else
    std::fill_n(p, count, value);
}
}  // namespace

// Rows that span the whole width are one contiguous run of pixels, filled at once (a pixel's
// samples are contiguous: a run of pixels is a run of values).
void clear_rect(const PixelRect& r, const FrameRaster& frame) {
  const size_t width = size_t(frame.target.width), samples = size_t(frame.target.samples);
  const bool whole_rows = r.x0 == 0 && size_t(r.x1) + 1 == width;
  const size_t count = (whole_rows ? width * size_t(r.y1 - r.y0 + 1) : size_t(r.x1 - r.x0 + 1)) * samples;
  const int32_t y_end = whole_rows ? r.y0 : r.y1;
  for (int32_t y = r.y0; y <= y_end; ++y) {
    const size_t row = (size_t(y) * width + size_t(r.x0)) * samples;
    fill_words(frame.target.owner + row, count, kOwnerBackground, frame.avx2);
    if (frame.target.depth) fill_words(frame.target.depth + row, count, frame.depth_clear_raw, frame.avx2);
  }
}

bool raster_scalar(const FastTriangle& t, const PixelRect& r, const DepthTestState& depth, const TileTarget& target) {
  PlaneSet edges;
  for (int i = 0; i < 3; ++i) {
    const int j = i == 2 ? 0 : i + 1;
    edges.push(make_edge(FixedPoint{Fixed24_8{t.x_fixed[i]}, Fixed24_8{t.y_fixed[i]}},
                         FixedPoint{Fixed24_8{t.x_fixed[j]}, Fixed24_8{t.y_fixed[j]}}, TieBreak::TopLeft));
  }
  const DepthPlane plane{t.a0, t.dzdx, t.dzdy};
  bool wrote = false;
  for (int32_t py = r.y0; py <= r.y1; ++py) {
    for (int32_t px = r.x0; px <= r.x1; ++px) {
      if (first_failing_plane(edges, int64_t(px) * kFixedOne, int64_t(py) * kFixedOne) >= 0) continue;
      const size_t i = size_t(py) * size_t(target.width) + size_t(px);
      if (depth.active) {
        const SampleDepth d = sample_depth(plane, t.offset, float(px), float(py), depth.range, depth.format, depth.fma);
        if (!depth_test_passes(depth.op, depth.format, d.raw, target.depth[i])) continue;
        if (depth.write) target.depth[i] = d.raw;
      }
      target.owner[i] = t.owner;
      wrote = true;
    }
  }
  return wrote;
}

}  // namespace rastercmp::cpu::fast
