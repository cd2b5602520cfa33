#include "cpu_raster/fast/band_worker.hpp"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/pipeline_cull.hpp"
#include "cpu_raster/exact/triangle_setup.hpp"
#include "cpu_raster/fast/block_rows.hpp"
#include "cpu_raster/fast/clipped_pieces.hpp"
#include "cpu_raster/fast/small_block_input.hpp"
#include "cpu_raster/fast/tile_depth_bounds.hpp"
#include "cpu_raster/fast/tile_edges.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu::fast {
namespace {

WindowVertex window_of(const FastVertex& v) { return WindowVertex{v.x, v.y, v.z}; }

// Whether an edge reaches |dx| + |dy| >= 2^23 fixed units (binned_triangle.hpp in_direct_range),
// which an unclipped triangle can only do corner to corner of a 16384-pixel viewport: a float
// pre-test (32768 px, less a margin for the snapping), then the snapped values.
bool edges_leave_direct_range(const FastVertex& v0, const FastVertex& v1, const FastVertex& v2) {
  const auto near_long = [](const FastVertex& a, const FastVertex& b) {
    return std::fabs(a.x - b.x) + std::fabs(a.y - b.y) >= 32760.0f;
  };
  if (!near_long(v0, v1) && !near_long(v1, v2) && !near_long(v2, v0)) return false;
  const auto fixed = [](const FastVertex& v) {
    return FixedPoint{Fixed24_8{snap_fixed(v.x)}, Fixed24_8{snap_fixed(v.y)}};
  };
  return !in_direct_range({fixed(v0), fixed(v1), fixed(v2)});
}

}  // namespace

BandWorker::BandWorker(FastFrame& frame, uint32_t index) : frame_(frame), index_(index) {
  batch_.reserve(kBatchSize);
  clipped_next_.assign(frame.draws.size(), 0);
  const int32_t rows = std::max(frame.raster.tiles_y, 0), columns = std::max(frame.raster.tiles_x, 0);
  owned_before_.assign(size_t(rows) + 1, 0);
  whole_before_.assign(size_t(rows) + 1, 0);
  row_kind_.assign(size_t(rows), 0);
  owned_first_.assign(size_t(rows), columns);
  owned_last_.assign(size_t(rows), -1);
  for (int32_t r = 0; r < rows; ++r) {
    int32_t owned = 0;
    for (int32_t tx = 0; tx < columns; ++tx) {
      if (!owns_tile(tx, r)) continue;
      ++owned;
      owned_first_[size_t(r)] = std::min(owned_first_[size_t(r)], tx);
      owned_last_[size_t(r)] = tx;
    }
    runs_ &= owned == 0 || owned == owned_last_[size_t(r)] - owned_first_[size_t(r)] + 1;
    row_kind_[size_t(r)] = owned == 0 ? 0 : owned == columns ? 1 : 2;
    shared_ |= row_kind_[size_t(r)] == 2;
    owned_before_[size_t(r) + 1] = owned_before_[size_t(r)] + (owned > 0 ? 1 : 0);
    whole_before_[size_t(r) + 1] = whole_before_[size_t(r)] + (owned == columns ? 1 : 0);
    if (row_kind_[size_t(r)] == 2) run_row_ = r;
  }
  if (!runs_ || owned_before_[size_t(rows)] != 1 || run_row_ < 0) run_row_ = -1;
}

void BandWorker::run() {
  for (uint32_t d = 0; d < frame_.draws.size(); ++d) {
    if (frame_.draws[d].fast)
      walk_fast(d);
    else if (!walk_exact(d))
      return;  // a primitive threw: the render throws it (FastFrame::failure)
    flush(frame_.draws[d].raster);
  }
  for (int32_t ty = 0; ty < frame_.raster.tiles_y; ++ty) {
    if (!owns_tile_row(ty)) continue;
    clear_tile_row(ty, index_, frame_.raster);
    if (frame_.packed_owner) pack_tile_row(ty, index_);
  }
  // the rows nobody owns: each taken by one worker, the first to get here taking more
  for (size_t i = frame_.next_unowned++; i < frame_.unowned_rows.size(); i = frame_.next_unowned++) {
    clear_tile_row(frame_.unowned_rows[i], kUnownedRow, frame_.raster);
    if (frame_.packed_owner) pack_tile_row(frame_.unowned_rows[i], kUnownedRow);
  }
}

// A frame drawn at a wider row pitch (FastFrame::packed_owner): the tiles of row tile_y that
// `worker` draws, final once its walk is done, copied into the result's attachments at the
// frame's width, each run of them a row at a time. Every tile is some worker's or in a row
// nobody owns, so every pixel is copied once.
void BandWorker::pack_tile_row(int32_t tile_y, uint32_t worker) {
  const RenderTargets& t = frame_.targets;
  const size_t samples = t.samples, pitch = size_t(t.width) * samples;
  const int32_t width = int32_t(frame_.scene->width);
  const size_t packed = size_t(width) * samples;
  const int32_t y0 = tile_y * kTileSize, y1 = std::min(y0 + kTileSize, int32_t(t.height));
  for (int32_t tx = 0; tx < frame_.raster.tiles_x; ++tx) {
    if (frame_.raster.tile(tx, tile_y).worker != worker) continue;
    int32_t last = tx;
    while (last + 1 < frame_.raster.tiles_x && frame_.raster.tile(last + 1, tile_y).worker == worker) ++last;
    const size_t x0 = size_t(tx) * kTileSize, x1 = std::min(size_t(last + 1) * kTileSize, size_t(width));
    const size_t values = (x1 - x0) * samples;
    for (int32_t y = y0; y < y1; ++y) {
      const size_t from = size_t(y) * pitch + x0 * samples, to = size_t(y) * packed + x0 * samples;
      std::copy_n(t.owner.data() + from, values, frame_.packed_owner + to);
      if (frame_.packed_depth) std::copy_n(t.depth_raw.data() + from, values, frame_.packed_depth + to);
    }
    tx = last;
  }
}

int32_t BandWorker::owned_tiles(int32_t tile_y, int32_t tile_x0, int32_t tile_x1) const {
  if (runs_) {
    const int32_t first = std::max(tile_x0, owned_first_[size_t(tile_y)]);
    const int32_t last = std::min(tile_x1, owned_last_[size_t(tile_y)]);
    return std::max(last - first + 1, 0);
  }
  tile_x0 = std::max(tile_x0, 0);
  tile_x1 = std::min(tile_x1, frame_.raster.tiles_x - 1);
  int32_t owned = 0;
  for (int32_t tx = tile_x0; tx <= tile_x1; ++tx) owned += owns_tile(tx, tile_y) ? 1 : 0;
  return owned;
}

bool BandWorker::owns_rect(int32_t x0, int32_t y0, int32_t x1, int32_t y1) const {
  const int32_t ty0 = std::max(y0 >> kTileOrder, 0), ty1 = std::min(y1 >> kTileOrder, frame_.raster.tiles_y - 1);
  for (int32_t ty = ty0; ty <= ty1; ++ty) {
    const uint8_t kind = row_kind_[size_t(ty)];
    if (kind == 1 || (kind == 2 && owned_tiles(ty, x0 >> kTileOrder, x1 >> kTileOrder) > 0)) return true;
  }
  return false;
}

// Any assignment of rows (not only r % workers, where any `workers` consecutive rows hold one of
// each worker's): the count of rows holding a tile of this worker's below t1 + 1 and below t0.
bool BandWorker::owns_tile_rows(int32_t t0, int32_t t1) const {
  t0 = std::max(t0, 0);
  t1 = std::min(t1, int32_t(owned_before_.size()) - 2);
  return t0 <= t1 && owned_before_[size_t(t1) + 1] != owned_before_[size_t(t0)];
}

void BandWorker::walk_fast(uint32_t d) {
  on_triangle_layout(
      frame_.scene->draws[d], [&](auto topology, auto indexed) { walk_triangles<topology(), indexed()>(d); },
      [] {});  // not a fast draw (render_fast.cpp)
}

template <Topology T, bool Indexed>
void BandWorker::walk_triangles(uint32_t d) {
  const Draw& draw = frame_.scene->draws[d];
  if (frame_.draws[d].small_blocks) return walk_small_blocks<T, Indexed>(d);
  const uint32_t* indices = draw.indices.data();
  const uint32_t count = primitive_count(draw);
  for (uint32_t i = 0; i < count; ++i) {
    const std::array<uint32_t, 3> n = vertex_numbers<T>(i);
    if constexpr (Indexed)
      triangle(d, i, indices[n[0]], indices[n[1]], indices[n[2]]);
    else
      triangle(d, i, n[0], n[1], n[2]);
  }
}

// The draw eight triangles at a time. Every worker sets up only the blocks that may reach its
// rows (block_tile_rows); it never waits for another worker. On AVX-512 hosts two such blocks in
// a row are set up together (the sixteen-wide set-up), then drawn one after the other.
template <Topology T, bool Indexed>
void BandWorker::walk_small_blocks(uint32_t d) {
  const FastDraw& fd = frame_.draws[d];
  const Draw& draw = frame_.scene->draws[d];
  const uint32_t count = primitive_count(draw);
  const uint32_t blocks = (count + 7) / 8;
  const SmallPairSetupFn pair_setup = frame_.raster.small_pair_setup;
  const uint32_t* const block_rows = fd.block_rows;  // null: one worker owns every row
  // Whether this worker sets block b up; its corners filled into `slot` when its rows are this
  // worker's and, in a shared row, its columns (known_want, or from the corners: wants_by_corners).
  const auto wanted = [&](uint32_t b, SmallBlock& slot) {
    const uint32_t rows = block_rows ? block_rows[b] : kBlockAnyRow;
    if (rows != kBlockAnyRow) {
      const int32_t lo = int32_t(rows & 0xFFFFu), hi = int32_t(rows >> 16);
      if (lo > hi || !owns_tile_rows(lo, hi)) return false;
    }
    const Want known = shared_ ? known_want(d, rows, b) : Want::Yes;
    if (known == Want::No) return false;
    fill_block_corners<T, Indexed>(draw.indices.data(), count, b, slot);
    return known == Want::Yes || wants_by_corners(d, rows, slot);
  };
  fill_block_draw(frame_, d, block_);
  fill_block_draw(frame_, d, next_block_);
  const uint32_t* const group_rows = fd.group_rows;
  uint32_t group_end = 0;  // the groups of the blocks before it are tested
  for (uint32_t b = 0; b < blocks; ++b) {
    // a group none of whose blocks reaches this worker's rows: skipped whole (wanted() would
    // refuse each of its blocks by its rows)
    if (group_rows && b >= group_end) {
      const uint32_t rows = group_rows[b / kGroupBlocks];
      group_end = (b / kGroupBlocks + 1) * kGroupBlocks;
      const int32_t lo = int32_t(rows & 0xFFFFu), hi = int32_t(rows >> 16);
      if (rows != kBlockAnyRow && (lo > hi || !owns_tile_rows(lo, hi))) {
        b = std::min(group_end, blocks) - 1;
        continue;
      }
    }
    // a run of blocks nobody sets up, or, for a unit of one run of tiles, of blocks that reach
    // none of its tiles: skipped eight at a time (small blocks: AVX2 hosts only)
    if (block_rows && run_row_ >= 0) {
      const int32_t row = run_row_;
      const uint32_t scan_end = group_rows ? std::min(group_end, blocks) : blocks;  // to the next group's test
      b = next_block_in_run_avx2(block_rows, fd.block_columns, b, scan_end, row, owned_first_[size_t(row)],
                                 owned_last_[size_t(row)]);
      if (b == scan_end) {
        b = scan_end - 1;
        continue;
      }
    } else if (block_rows && block_rows[b] == kNoRow) {
      b = next_reaching_block_avx2(block_rows, b, blocks);
      if (b == blocks) break;
    }
    if (!wanted(b, block_)) continue;
    if (pair_setup != nullptr && b + 1 < blocks && wanted(b + 1, next_block_)) {
      ++b;
      pair_setup(block_.in, next_block_.in, block_.out, next_block_.out);
      draw_block(d, block_);
      draw_block(d, next_block_);
      continue;
    }
    frame_.raster.small_setup(block_.in, block_.out);
    draw_block(d, block_);
  }
}

// Set-up of an unclipped triangle: triangle_setup.cpp step by step (docs/lavapipe-rules.md §2.2-§2.5,
// §3.2, §4.3), with the snap already done per vertex and the rows test first.
void BandWorker::triangle(uint32_t d, uint32_t primitive, uint32_t a, uint32_t b, uint32_t c) {
  const FastDraw& fd = frame_.draws[d];
  const FastVertex& v0 = fd.vertices[a];
  const FastVertex& v1 = fd.vertices[b];
  const FastVertex& v2 = fd.vertices[c];
  const uint32_t flags = v0.flags | v1.flags | v2.flags;
  if (flags & kVertexClipBits) {
    if (needs_clipping(v0.flags, v1.flags, v2.flags)) clipped_triangle(d, primitive, a, b, c);
    return;  // otherwise all three outside one plane: ClipFate::Outside
  }
  if (flags & kVertexSnapFailed) return;       // SetupFate::NonFinite
  if (edges_leave_direct_range(v0, v1, v2)) {  // llvmpipe's int32 set-up wraps: the exact path's (§7.5)
    const RasterState& state = frame_.scene->draws[d].state;
    const std::array<WindowVertex, 3> window{window_of(v0), window_of(v1), window_of(v2)};
    if (fd.pipelined(primitive) && state.cull_mode != CullMode::None &&
        pipeline_cull_drops(pipeline_cull_determinant(window), state.cull_mode, state.front_face))
      return;
    const TriangleSetup setup = setup_triangle(window, encode_owner(d, primitive), fd.setup);
    if (setup.fate != SetupFate::Rasterized) return;
    if (!batch_.empty()) flush(fd.raster);
    raster_exact_in_band(setup.raster, fd.raster.depth);
    return;
  }
  const PixelRect& region = frame_.exact.region;
  const int32_t fy[3] = {snap_fixed(v0.y), snap_fixed(v1.y), snap_fixed(v2.y)};  // §2.2
  // triangle_bbox (x0 = min >> 8, x1 = (max - 1) >> 8) ∩ draw region holds the coverage (§2.5);
  // so does the tighter x0 = (min + 255) >> 8: the sample of pixel x lies at x * 256, and one left
  // of (or above) every corner is outside the triangle. The tighter rectangle keeps a column or
  // row that can hold no fragment out of the depth bounds' "values under r" (tile_raster.cpp).
  const int32_t y0 = std::max((std::min({fy[0], fy[1], fy[2]}) + kFixedOne - 1) >> kFixedOrder, region.y0);
  const int32_t y1 = std::min((std::max({fy[0], fy[1], fy[2]}) - 1) >> kFixedOrder, region.y1);
  if (y0 > y1 || !owns_tile_rows(y0 >> kTileOrder, y1 >> kTileOrder)) return;
  const int32_t fx[3] = {snap_fixed(v0.x), snap_fixed(v1.x), snap_fixed(v2.x)};
  const int32_t x0 = std::max((std::min({fx[0], fx[1], fx[2]}) + kFixedOne - 1) >> kFixedOrder, region.x0);
  const int32_t x1 = std::min((std::max({fx[0], fx[1], fx[2]}) - 1) >> kFixedOrder, region.x1);
  if (x0 > x1 || (shared_ && !owns_rect(x0, y0, x1, y1))) return;
  // area = dx01*dy20 - dx20*dy01 (§2.3), int64
  const int64_t area =
      int64_t(fx[0] - fx[1]) * int64_t(fy[2] - fy[0]) - int64_t(fx[2] - fx[0]) * int64_t(fy[0] - fy[1]);
  if (area == 0) return;  // always dropped
  const RasterState& state = frame_.scene->draws[d].state;
  if (face_culled((area > 0) == (state.front_face == FrontFace::CounterClockwise), state.cull_mode)) return;
  if (fd.pipelined(primitive) && state.cull_mode != CullMode::None &&  // draw_pipe_cull.c (§2.6)
      pipeline_cull_drops(pipeline_cull_determinant({window_of(v0), window_of(v1), window_of(v2)}), state.cull_mode,
                          state.front_face))
    return;
  const int k1 = area < 0 ? 2 : 1, k2 = 3 - k1;  // rotate_fixed_position_12: (v0, v2, v1)
  const FastVertex& w1 = k1 == 1 ? v1 : v2;
  const FastVertex& w2 = k1 == 1 ? v2 : v1;
  FastTriangle t;
  t.x_fixed[0] = fx[0], t.x_fixed[1] = fx[k1], t.x_fixed[2] = fx[k2];
  t.y_fixed[0] = fy[0], t.y_fixed[1] = fy[k1], t.y_fixed[2] = fy[k2];
  t.rect = PixelRect{x0, y0, x1, y1};
  t.owner = encode_owner(d, primitive);
  if (fd.setup.depth_active()) {
    const std::array<WindowVertex, 3> window{window_of(v0), window_of(w1), window_of(w2)};
    const DepthPlane plane = triangle_depth_plane(window, 0.5f);
    t.a0 = plane.a0;
    t.dzdx = plane.dzdx;
    t.dzdy = plane.dzdy;
    if (state.depth_bias.enable)
      t.offset =
          triangle_depth_offset(window, state.depth_bias, fd.setup.depth_format, true, unorm_bias_units(fd.setup.rules))
              .offset;
  }
  submit(t, fd.raster);
}

// A triangle that needs clipping: its pieces from the block-row phase's table when it is there
// (clipped_pieces.hpp; the table is empty with one worker and for draws not set up eight at a
// time), else the exact path's clipper and set-up here (for_each_piece); the pieces that reach
// this worker's tiles are drawn, in the clipper's order.
void BandWorker::clipped_triangle(uint32_t d, uint32_t primitive, uint32_t a, uint32_t b, uint32_t c) {
  const FastDraw& fd = frame_.draws[d];
  const auto draw_piece = [&](const FastTriangle& t) {
    if (!t.rect.empty() && owns_rect(t.rect.x0, t.rect.y0, t.rect.x1, t.rect.y1)) submit(t, fd.raster);
  };
  const std::vector<ClippedEntry>& list = fd.clipped;
  size_t& next = clipped_next_[d];  // the walk meets a draw's primitives in increasing order
  while (next < list.size() && list[next].primitive < primitive) ++next;
  if (next < list.size() && list[next].primitive == primitive && !list[next].in_place) {
    const ClippedEntry& entry = list[next];
    for (uint32_t k = 0; k < entry.count; ++k) draw_piece(entry.pieces[k]);
    return;
  }
  for_each_piece(frame_, d, primitive, a, b, c, draw_piece, [&](const RasterPrimitive& binned) {
    if (!batch_.empty()) flush(fd.raster);  // llvmpipe's wrapping arithmetic: the exact rasterizer, in order
    raster_exact_in_band(binned, fd.raster.depth);
  });
}

// Every triangle, one tile or several, joins the batch (a one-tile triangle used to flush it and
// be drawn at once: with perspective's mix of sizes that flushed after 2.6 triangles on average).
void BandWorker::submit(const FastTriangle& t, const DrawRaster& raster) {
  batch_.push_back(t);
  if (batch_.size() == kBatchSize) flush(raster);
}

// The draw's raster, or its copy without depth bounds once the audit turned them off.
const DrawRaster& BandWorker::audited(const DrawRaster& raster) {
  if (audit_.draw != &raster) {
    audit_ = BoundsAudit{};
    audit_.draw = &raster;
  }
  return audit_.off ? audit_.without : raster;
}

void BandWorker::count_bounds(BoundsUse use) {
  if (use == BoundsUse::None) return;
  ++audit_.consulted;
  if (use == BoundsUse::Helped) ++audit_.helped;
  if (!audit_.off && audit_.consulted >= kAuditCalls && audit_.helped * kAuditRatio < audit_.consulted) {
    audit_.off = true;
    audit_.without = *audit_.draw;
    audit_.without.bounds = false;
  }
}

// Tile by tile over the batch's union, each tile's triangles in submission order, from the first
// whose writes are not all replaced by a later one (first_visible). A tile visits only the
// triangles whose rectangle reaches it (bin_batch): the others would draw nothing there.
void BandWorker::flush(const DrawRaster& draw_raster) {
  if (batch_.empty()) return;
  const DrawRaster& raster = audited(draw_raster);
  PixelRect all = batch_.front().rect;
  for (const FastTriangle& t : batch_)
    all = PixelRect{std::min(all.x0, t.rect.x0), std::min(all.y0, t.rect.y0), std::max(all.x1, t.rect.x1),
                    std::max(all.y1, t.rect.y1)};
  const int32_t tx0 = all.x0 >> kTileOrder, ty0 = all.y0 >> kTileOrder;
  const int32_t tx1 = all.x1 >> kTileOrder, ty1 = all.y1 >> kTileOrder;
  bin_batch(tx0, ty0, tx1, ty1);
  size_t k = 0;
  for (int32_t ty = ty0; ty <= ty1; ++ty) {
    for (int32_t tx = tx0; tx <= tx1; ++tx, ++k) {
      const uint8_t* list = bin_list_.data() + bin_first_[k];
      const size_t count = bin_first_[k + 1] - bin_first_[k];
      if (count == 0) continue;  // also every tile of a row this worker does not draw
      const PixelRect tile = tile_rect(tx, ty, frame_.raster.target);
      if (may_hide(tile, list, count, raster)) {  // prepared once, drawn from the first visible
        const size_t first = first_visible(tile, list, count, raster);
        count_bounds(first > 0 ? BoundsUse::Helped : BoundsUse::PerPixel);
        for (size_t i = first; i < count; ++i)
          count_bounds(raster_prepared(batch_[list[i]], prepared_[i], tx, ty, raster, frame_.raster));
        continue;
      }
      for (size_t i = 0; i < count; ++i) {
        const FastTriangle& t = batch_[list[i]];
        count_bounds(raster_in_tile(t, rect_in_tile(t.rect, tile), tx, ty, raster, frame_.raster));
      }
    }
  }
  batch_.clear();
}

// The per-tile lists of flush over tiles [tx0, tx1] x [ty0, ty1] (a counting sort: each triangle
// counted in the tiles of its rectangle, then placed; rows of other workers get no entry).
void BandWorker::bin_batch(int32_t tx0, int32_t ty0, int32_t tx1, int32_t ty1) {
  static_assert(kBatchSize <= 256, "batch indices are bytes");
  const int32_t columns = tx1 - tx0 + 1;
  bin_first_.assign(size_t(columns) * size_t(ty1 - ty0 + 1) + 1, 0);
  const auto for_each_tile = [&](const FastTriangle& t, auto&& visit) {
    for (int32_t ty = t.rect.y0 >> kTileOrder; ty <= t.rect.y1 >> kTileOrder; ++ty) {
      if (!owns_tile_row(ty)) continue;
      const bool shared_row = row_kind_[size_t(ty)] == 2;
      for (int32_t tx = t.rect.x0 >> kTileOrder; tx <= t.rect.x1 >> kTileOrder; ++tx)
        if (!shared_row || owns_tile(tx, ty)) visit(size_t(ty - ty0) * size_t(columns) + size_t(tx - tx0));
    }
  };
  for (const FastTriangle& t : batch_) for_each_tile(t, [&](size_t k) { ++bin_first_[k + 1]; });
  for (size_t k = 1; k < bin_first_.size(); ++k) bin_first_[k] += bin_first_[k - 1];
  bin_list_.resize(bin_first_.back());
  std::vector<uint32_t>& next = bin_next_;
  next.assign(bin_first_.begin(), bin_first_.end() - 1);
  for (size_t i = 0; i < batch_.size(); ++i)
    for_each_tile(batch_[i], [&](size_t k) { bin_list_[next[k]++] = uint8_t(i); });
}

// Whether a triangle of the tile's list may replace every value an earlier one leaves in the tile
// (first_visible): depth bounds and writes on, and a triangle after the first whose rectangle
// holds the whole tile.
bool BandWorker::may_hide(const PixelRect& tile, const uint8_t* list, size_t count, const DrawRaster& raster) const {
  if (!raster.bounds || !raster.depth.write) return false;
  for (size_t i = 1; i < count; ++i)
    if (rect_in_tile(batch_[list[i]].rect, tile) == tile) return true;
  return false;
}

// The position in the tile's list of the last triangle that covers every pixel of the tile and
// passes the depth test against every fragment the list's earlier triangles have in it (their
// ranges), with depth writes on. Wherever an earlier triangle writes, the tile then holds one of
// those fragments when this triangle comes, so it writes there too and replaces what the earlier
// one left; wherever no earlier triangle writes, leaving them out changes nothing. Drawing from it
// therefore gives the same bytes ("occluded batch triangles", docs/performance-log.md, 62f382b); it is
// itself drawn as always, against what the tile holds. 0 when there is none or nothing can be
// proven. Fills prepared_[i] with list[i]'s edges and range in the tile (prepare_in_tile), which
// flush then draws from.
size_t BandWorker::first_visible(const PixelRect& tile, const uint8_t* list, size_t count, const DrawRaster& raster) {
  prepared_.resize(count);
  bool earlier = false, provable = true;
  TileBounds fragments{UINT32_MAX, 0, BoundsState::Exact};  // range of the earlier triangles' fragments
  size_t first = 0;
  for (size_t i = 0; i < count; ++i) {
    TileTriangle& p = prepared_[i];
    const FastTriangle& t = batch_[list[i]];
    p = prepare_in_tile(t, rect_in_tile(t.rect, tile), raster, true);
    if (p.edges.fit == EdgeFit::None || !provable) continue;  // no sample of the rectangle in the triangle
    if (!p.ranged) {
      provable = false;  // nothing later can be proven
      continue;
    }
    if (earlier && p.covers(tile) && classify_depth(raster.depth.op, p.fragment, fragments) == DepthVerdict::AllPass)
      first = i;
    fragments.zmin = std::min(fragments.zmin, p.fragment.lo);
    fragments.zmax = std::max(fragments.zmax, p.fragment.hi);
    earlier = true;
  }
  return first;
}

}  // namespace rastercmp::cpu::fast
