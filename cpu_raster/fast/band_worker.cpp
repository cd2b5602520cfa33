#include "cpu_raster/fast/band_worker.hpp"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/clip_line.hpp"
#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/clip_vertex.hpp"
#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"
#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/pipeline_cull.hpp"
#include "cpu_raster/exact/triangle_setup.hpp"
#include "cpu_raster/fast/block_rows.hpp"
#include "cpu_raster/fast/clipped_pieces.hpp"
#include "cpu_raster/fast/exact_rows.hpp"
#include "cpu_raster/fast/lean_setup.hpp"
#include "cpu_raster/fast/small_block_input.hpp"
#include "cpu_raster/fast/tile_depth_bounds.hpp"
#include "cpu_raster/fast/tile_edges.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu::fast {
namespace {

// set_up() watched for the MXCSR's denormal flags (DE, UE): read before (cleared when raised) and
// after, written only when raised; `raised` says whether set_up raised one. Its result.
template <class SetUp>
auto watch_denormal_flags(SetUp&& set_up, bool& raised) {
  if (denormal_flags_raised()) clear_denormal_flags();
  auto result = set_up();
  raised = denormal_flags_raised();
  if (raised) clear_denormal_flags();
  return result;
}

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
  for (int32_t ty = 0; ty < frame_.raster.tiles_y; ++ty)
    if (owns_tile_row(ty)) clear_tile_row(ty, index_, frame_.raster);
  // the rows nobody owns: each taken by one worker, the first to get here taking more
  for (size_t i = frame_.next_unowned++; i < frame_.unowned_rows.size(); i = frame_.next_unowned++)
    clear_tile_row(frame_.unowned_rows[i], kUnownedRow, frame_.raster);
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
  const std::vector<ClippedPrimitive>& list = fd.clipped.primitives;
  size_t& next = clipped_next_[d];  // the walk meets a draw's primitives in increasing order
  while (next < list.size() && list[next].primitive < primitive) ++next;
  if (next < list.size() && list[next].primitive == primitive && !list[next].in_place) {
    const ClippedPrimitive& entry = list[next];
    for (uint32_t k = entry.first; k < entry.first + entry.count; ++k) draw_piece(fd.clipped.pieces[k]);
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

// Draws the fast path does not handle: the exact front end, each primitive's visit rectangle cut
// to this worker's tile rows, and the exact rasterizer's evaluation on the same targets (each row's
// columns cut to the primitive's, exact_rows.hpp). A primitive that cannot reach this worker's
// rows is left out before its clipping and set-up (misses_own_rows).
bool BandWorker::walk_exact(uint32_t d) {
  const FrameContext& frame = frame_.exact;
  const DepthTestState& depth = frame_.draws[d].raster.depth;
  // the vertex phase's window positions and clip bits (fast_vertices.hpp: make_clip_vertex's
  // operations), where it ran for this draw; its clip bits also give the chunk flags
  const FastVertex* transformed = frame_.draws[d].vertices;
  const size_t positions = frame_.scene->draws[d].positions_clip.size();
  const DrawWalk walk = transformed ? begin_draw_transformed(d) : begin_draw(frame, d);
  const OutcomeSink sink = [&](const PrimitiveOutcome& outcome) {
    if (outcome.rasterized()) raster_exact_in_band(outcome.raster, depth);
  };
  const bool lines = walk.base.is_line, depth_clip = walk.draw->state.depth_clip_enabled();
  // How far a primitive's visit rectangle reaches past its vertices' window y: a line's quad its
  // half width, a Bresenham end's shift (at most one pixel) and the rounded-up box; a triangle's
  // box and the multisample scissor quirk one row each.
  const float margin = lines ? std::max(walk.draw->state.line_width, 1.0f) + 3.0f : 2.0f;
  const uint32_t corners = lines ? 2 : 3;
  // Lines: run_line's calls (clip, set-up in the primitive's mode) without the outcome's
  // bookkeeping. A triangle run_triangle would pass unclipped to set-up, without the pipeline's
  // float cull, in the flushed mode: the lean set-up (lean_setup.hpp) from its corners. The
  // clipper returns a triangle with every vertex inside unchanged unless the clip skip is off
  // (clip_triangle); anything else takes run_primitive.
  const bool lean_triangles = !lines && frame.skips.clip_only_when_needed;
  const bool float_cull = walk.draw->state.cull_mode != CullMode::None;
  const uint32_t inside_planes = frame.skips.clip_only_when_needed ? 0 : tested_clip_planes(depth_clip);
  const bool bias_denormal = lines && depth_bias_is_denormal(walk.draw->state.depth_bias);
  const LineXyClip line_xy = frame.rules.has(LavapipeRule::LineGuardBand) ? LineXyClip::GuardBand : LineXyClip::Clip;
  // A line or triangle list: primitive i's corners are positions (indices[]) corners * i + k, so a
  // primitive in other workers' rows is left out from the vertex phase's values before it is
  // assembled.
  const bool listed = transformed && frame_.workers > 1 &&
                      walk.draw->topology == (lines ? Topology::LineList : Topology::TriangleList);
  // A primitive that throws (set-up in a mode where the two modes disagree, a refused wrapping
  // set-up) stops this walk; the render throws the first such primitive's error (FastFrame::failure).
  uint32_t i = 0;
  try {
    for (; i < walk.count; ++i) {
      if (listed) {
        const RowReach reach = listed_reach(*walk.draw, transformed, positions, corners, i, margin);
        if (reach == RowReach::OtherRows) continue;
        if (reach == RowReach::NoFrameRow && primitive_setup_denormals(walk, i) == SetupDenormals::Flushed) continue;
      }
      const SetupDenormals mode = primitive_setup_denormals(walk, i);
      const bool flushed = mode == SetupDenormals::Flushed;
      if (!lines && frame_.workers == 1 && (!flushed || !lean_triangles)) {
        run_primitive(frame, walk, i, sink);
        continue;
      }
      const AssembledPrimitive prim = assemble_primitive(*walk.draw, i);
      std::array<ClipVertex, 3> v;
      for (uint32_t k = 0; k < corners; ++k) {
        const uint32_t position = prim.position[k];
        if (transformed && position < positions) {  // make_clip_vertex's fields
          const FastVertex& t = transformed[position];
          v[k].pos_clip = walk.draw->positions_clip[position];
          v[k].window = WindowVertex{t.x, t.y, t.z};
          v[k].clip_mask = t.flags & kVertexClipBits;
        } else {
          v[k] = make_clip_vertex(walk.draw->positions_clip[position], frame.viewport, depth_clip, frame.fma);
        }
      }
      // a listed primitive had this test on these values above
      if (frame_.workers > 1 && !listed && misses_own_rows(v.data(), corners, margin, !flushed)) continue;
      const uint32_t owner = encode_owner(d, prim.primitive_index);
      if (lines) {
        const ClippedLine clipped = clip_line({v[0], v[1]}, frame.viewport, inside_planes, line_xy);
        if (clipped.fate == ClipFate::Outside || clipped.fate == ClipFate::Discarded) continue;
        const std::array<WindowVertex, 2> window{clipped.line[0].window, clipped.line[1].window};
        const bool lean_line = frame_.raster.avx2 && (flushed || !bias_denormal);
        const LeanSetup lean =
            lean_line ? setup_line_lean_flushed(flushed, window, owner, walk.ctx) : LeanSetup::Full;
        if (lean == LeanSetup::Drawn) raster_exact_in_band(lean_, depth);
        if (lean != LeanSetup::Full) continue;
        const LineSetup setup =
            setup_line_flushed(mode, window, owner, walk.ctx, prim.primitive_index, bias_denormal);
        if (setup.fate == SetupFate::Rasterized) raster_exact_in_band(setup.raster, depth);
        continue;
      }
      const bool inside = (v[0].clip_mask | v[1].clip_mask | v[2].clip_mask) == 0;
      if (!flushed || !lean_triangles || !inside || (float_cull && walk.pipelined[i / walk.per_chunk])) {
        run_primitive(frame, walk, i, sink);
        continue;
      }
      const std::array<WindowVertex, 3> window{v[0].window, v[1].window, v[2].window};
      // the workers run with denormals flushed (WorkerPool::call, render_fast_into)
      const LeanSetup lean = frame_.raster.avx2 ? setup_triangle_lean(window, owner, walk.ctx, lean_) : LeanSetup::Full;
      if (lean == LeanSetup::Drawn) raster_exact_in_band(lean_, depth);
      if (lean != LeanSetup::Full) continue;
      const TriangleSetup setup =
          setup_triangle_in_mode(SetupDenormals::Flushed, window, owner, walk.ctx, prim.primitive_index);
      if (setup.fate == SetupFate::Rasterized) raster_exact_in_band(setup.raster, depth);
    }
  } catch (...) {
    frame_.record_failure(d, i, std::current_exception());
    return false;
  }
  return true;
}

// setup_line_in_mode in a worker, which runs with denormals flushed: a line set up in the flushed
// mode is setup_line's result as it is; one in a trailing run (Kept, EitherMustAgree) is too when
// no set-up operation met a denormal and no bias factor is one (setup_in_mode, front_end.cpp), and
// otherwise goes to setup_line_in_mode, which sets it up again in both modes. The MXCSR's flags are
// read before and after, and written only when raised: one write in place of the scoped mode's and
// the watch's three per line.
LineSetup BandWorker::setup_line_flushed(SetupDenormals mode, const std::array<WindowVertex, 2>& window,
                                         uint32_t owner, const SetupContext& ctx, uint32_t primitive_index,
                                         bool bias_denormal) {
  if (mode == SetupDenormals::Flushed) return setup_line(window, owner, ctx);
  if (bias_denormal) return setup_line_in_mode(mode, window, owner, ctx, primitive_index);
  bool raised = false;
  LineSetup setup = watch_denormal_flags([&] { return setup_line(window, owner, ctx); }, raised);
  if (!raised) return setup;
  return setup_line_in_mode(mode, window, owner, ctx, primitive_index);
}

// setup_line_lean where setup_line_flushed would hand back setup_line's result: in the flushed
// mode, and in a trailing run's mode when no operation raised a denormal flag (the lean set-up
// makes setup_line's float operations in its order; its roundings raise none). Full otherwise, so
// that setup_line_flushed sets the line up again (in both modes when a flag was raised).
LeanSetup BandWorker::setup_line_lean_flushed(bool flushed, const std::array<WindowVertex, 2>& window, uint32_t owner,
                                              const SetupContext& ctx) {
  if (flushed) return setup_line_lean(window, owner, ctx, lean_);
  bool raised = false;
  const LeanSetup lean = watch_denormal_flags([&] { return setup_line_lean(window, owner, ctx, lean_); }, raised);
  return raised ? LeanSetup::Full : lean;
}

// begin_draw with the chunk flags and trailing run formed from the vertex phase's clip bits (as
// for the fast draws, render_fast.cpp). A position past the draw's counts as unclipped: such an
// index makes the render throw (the profile check) before any walk.
DrawWalk BandWorker::begin_draw_transformed(uint32_t d) const {
  const Draw& draw = frame_.scene->draws[d];
  const FastVertex* vertices = frame_.draws[d].vertices;
  const size_t positions = draw.positions_clip.size();
  const auto clipped = [vertices, positions](uint32_t position) {
    return position < positions && (vertices[position].flags & kVertexClipBits) != 0;
  };
  std::vector<bool> pipelined = pipelined_chunks_by(draw, clipped);
  const TrailingPipelineRun run = trailing_pipeline_run_of(draw, pipelined, clipped);
  return begin_draw(frame_.exact, d, std::move(pipelined), run);
}

// Whether a primitive certainly reaches none of this worker's tile rows: every vertex inside every
// clip plane (the clipper passes it unchanged, so these window positions are set-up's input),
// finite, spanning less than 32000 px in x plus y with the margin (so its edges stay in the direct
// range: no wrapping set-up, lavapipe-rules §7.5), and its window y extent widened by `margin` on
// each side in no row this worker owns. Leaving it out changes nothing in these rows. A primitive
// set up with denormals flushed then cannot throw. One set up in the other mode (`may_throw`)
// throws where the two modes disagree; it is left out only where its rows meet the frame's tile
// rows, every one of which some worker owns (row_balance, contiguous_rows): a worker that owns one
// sets it up, in order, and records its error (walk_exact, FastFrame::failure), which is then
// the first failing primitive's, as on the exact path.
bool BandWorker::misses_own_rows(const ClipVertex* v, uint32_t count, float margin, bool may_throw) const {
  const RowReach reach =
      reach_of(count, margin, [v](uint32_t k) { return std::pair{v[k].window, v[k].clip_mask}; });
  return reach == RowReach::OtherRows || (reach == RowReach::NoFrameRow && !may_throw);
}

// Primitive i of a line or triangle list (`corners` a primitive), from the vertex phase's values
// at its positions: Unsettled when one lies past the draw's positions (the walk's own path then
// takes it) or the list ends before its last corner.
BandWorker::RowReach BandWorker::listed_reach(const Draw& draw, const FastVertex* transformed, size_t positions,
                                              uint32_t corners, uint32_t i, float margin) const {
  std::array<uint32_t, 3> at{};
  const size_t first = size_t(corners) * i, listed = draw.indices.empty() ? positions : draw.indices.size();
  if (first + corners > listed) return RowReach::Unsettled;
  for (uint32_t k = 0; k < corners; ++k) {
    at[k] = draw.indices.empty() ? uint32_t(first + k) : draw.indices[first + k];
    if (at[k] >= positions) return RowReach::Unsettled;
  }
  return reach_of(corners, margin, [&](uint32_t k) {
    const FastVertex& v = transformed[at[k]];
    return std::pair{WindowVertex{v.x, v.y, v.z}, v.flags & kVertexClipBits};
  });
}

template <class Vertex>
BandWorker::RowReach BandWorker::reach_of(uint32_t count, float margin, Vertex&& vertex) const {
  const WindowVertex first = vertex(0).first;
  float x_lo = first.x, x_hi = x_lo, y_lo = first.y, y_hi = y_lo;
  for (uint32_t k = 0; k < count; ++k) {
    const auto [window, clip_mask] = vertex(k);
    if (clip_mask != 0 || !std::isfinite(window.x) || !std::isfinite(window.y)) return RowReach::Unsettled;
    x_lo = std::min(x_lo, window.x);
    x_hi = std::max(x_hi, window.x);
    y_lo = std::min(y_lo, window.y);
    y_hi = std::max(y_hi, window.y);
  }
  if ((x_hi - x_lo) + (y_hi - y_lo) + 4.0f * margin >= 32000.0f || y_lo < -1e7f || y_hi > 1e7f)
    return RowReach::Unsettled;
  // floor of a float within +-2e7: its truncation, one less when that lies above it
  const auto floor_of = [](float value) {
    const int32_t t = int32_t(value);
    return float(t) > value ? t - 1 : t;
  };
  const int32_t row_lo = floor_of(y_lo - margin), row_hi = floor_of(y_hi + margin);
  if (owns_tile_rows(row_lo >> kTileOrder, row_hi >> kTileOrder)) return RowReach::OwnRows;
  return row_hi < 0 || (row_lo >> kTileOrder) >= frame_.raster.tiles_y ? RowReach::NoFrameRow : RowReach::OtherRows;
}

void BandWorker::raster_exact_in_band(const RasterPrimitive& primitive, const DepthTestState& depth) {
  const PixelRect& visit = primitive.visit;
  if (visit.empty()) return;
  // Most often every tile row of the visit is all this worker's: drawn whole, in one call (the visit
  // lies in the framebuffer, so the cut below would leave it as it is, in pieces).
  const int32_t ty_lo = visit.y0 >> kTileOrder, ty_hi = visit.y1 >> kTileOrder;
  if (ty_lo >= 0 && whole_before_[size_t(ty_hi) + 1] - whole_before_[size_t(ty_lo)] == uint32_t(ty_hi - ty_lo + 1)) {
    prepare_tiles(visit, depth.write);
    if (frame_.raster.avx512 && rasterize_box_avx512(primitive, visit.y0, visit.y1, depth, frame_.targets)) return;
    if (frame_.raster.avx2 &&
        rasterize_rows_avx2(primitive, visit.y0, visit.y1, depth, frame_.targets, frame_.raster.avx512))
      return;
    if (primitive.binned)
      rasterize_binned_rows(primitive, depth, frame_.targets, frame_.raster.avx2);
    else
      rasterize_primitive_rows(primitive, depth, frame_.targets, frame_.raster.avx2);
    return;
  }
  const int32_t tx_lo = std::max(visit.x0 >> kTileOrder, 0);
  const int32_t tx_hi = std::min(visit.x1 >> kTileOrder, frame_.raster.tiles_x - 1);
  for (int32_t ty = visit.y0 >> kTileOrder; ty <= visit.y1 >> kTileOrder; ++ty) {
    if (!owns_tile_row(ty)) continue;
    const int32_t y0 = std::max(visit.y0, ty * kTileSize), y1 = std::min(visit.y1, ty * kTileSize + kTileSize - 1);
    RasterPrimitive band = primitive;
    band.visit.y0 = y0;
    band.visit.y1 = y1;
    // each run of this worker's tiles in the row (the whole visit where the row is its own); a
    // sample's coverage and depth do not depend on the columns visited beside it
    for (int32_t tx = tx_lo; tx <= tx_hi; ++tx) {
      if (!owns_tile(tx, ty)) continue;
      int32_t last = tx;
      while (last < tx_hi && owns_tile(last + 1, ty)) ++last;
      band.visit.x0 = std::max(visit.x0, tx * kTileSize);
      band.visit.x1 = std::min(visit.x1, last * kTileSize + kTileSize - 1);
      tx = last;
      prepare_tiles(band.visit, depth.write);
      if (frame_.raster.avx512 && rasterize_box_avx512(band, y0, y1, depth, frame_.targets)) continue;
      if (frame_.raster.avx2 && rasterize_rows_avx2(band, y0, y1, depth, frame_.targets, frame_.raster.avx512))
        continue;
      if (band.binned)  // llvmpipe's wrapping set-up: coverage from its bins, not a plane test
        rasterize_binned_rows(band, depth, frame_.targets, frame_.raster.avx2);
      else
        rasterize_primitive_rows(band, depth, frame_.targets, frame_.raster.avx2);
    }
  }
}

// Before the exact rasterizer writes into r: its tiles cleared, their bounds dropped if depth is written.
void BandWorker::prepare_tiles(const PixelRect& r, bool depth_write) {
  for (int32_t ty = r.y0 >> kTileOrder; ty <= r.y1 >> kTileOrder; ++ty) {
    for (int32_t tx = r.x0 >> kTileOrder; tx <= r.x1 >> kTileOrder; ++tx) {
      TileState& tile = frame_.raster.tile(tx, ty);
      if (!tile.cleared) clear_tile_row(ty, index_, frame_.raster);
      if (depth_write) tile.bounds.state = BoundsState::Unknown;
    }
  }
}

}  // namespace rastercmp::cpu::fast
