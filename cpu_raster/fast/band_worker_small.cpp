// BandWorker's small-triangle blocks: drawing a set-up block into the worker's tiles, and the
// phase before the walks that measures which tile rows each block may reach.
#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>

#include "cpu_raster/fast/band_worker.hpp"
#include "cpu_raster/fast/block_rows.hpp"
#include "cpu_raster/fast/small_block_input.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu::fast {
namespace {

// Whether every lane of the block has all three corners outside one clip plane (the set-up drops
// such lanes: ClipFate::Outside); its indices already checked.
bool block_outside(const SmallBlockInput& in) {
  for (uint32_t l = 0; l < in.count; ++l) {
    const size_t at = size_t(l) * in.stride;
    if ((in.vertices[in.corners[0][at]].flags & in.vertices[in.corners[1][at]].flags &
         in.vertices[in.corners[2][at]].flags & kVertexClipBits) == 0)
      return false;
  }
  return true;
}

template <Topology T, bool Indexed>
bool measure_rows(FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end) {
  bool bad = false;
  const uint32_t positions = uint32_t(frame.scene->draws[d].positions_clip.size());
  if (positions == 0) return begin == end;                 // every corner would be out of range
  if constexpr (T == Topology::TriangleList && Indexed) {  // the full blocks of a mesh
    const uint32_t full_end = std::min(end, primitive_count(frame.scene->draws[d]) / 8);
    const uint32_t* indices = frame.scene->draws[d].indices.data();
    const int16_t* tile_rows = frame.draws[d].tile_rows;
    uint32_t* block_rows = frame.draws[d].block_rows;
    const PixelRect region = frame.exact.region;
    // small_blocks draws exist on AVX2 hosts only (AVX-512 hosts are AVX2 hosts too)
    while (begin < full_end) {
      const uint32_t n = std::min(kSpanBlocks, full_end - begin);
      const uint32_t* span = indices + 24 * size_t(begin);
      if (!span_tile_rows_avx2(span, n, tile_rows, positions, region, block_rows + begin))
        for (uint32_t b = 0; b < n; ++b)
          block_rows[begin + b] = list_block_tile_rows_avx2(span + 24 * size_t(b), tile_rows, positions, region, bad);
      begin += n;
    }
  }
  const uint32_t generic = begin;  // blocks before it were measured whole, outside ones included
  SmallBlock block;
  fill_block_draw(frame, d, block);
  const uint32_t count = primitive_count(frame.scene->draws[d]);
  for (uint32_t b = begin; b < end; ++b) {
    fill_block_corners<T, Indexed>(frame.scene->draws[d].indices.data(), count, b, block);
    frame.draws[d].block_rows[b] =
        block_tile_rows(block.in, frame.draws[d].tile_rows, positions, frame.exact.region, bad);
  }
  if (bad) return false;
  // A block with a clipped corner may reach any row, unless no lane has a corner inside the view
  // volume's planes (a camera's scene: most of the mesh behind, beside or past it): no worker sets
  // those up. (The full blocks of an indexed list got that answer from list_block_tile_rows_avx2.)
  for (uint32_t b = generic; b < end; ++b) {
    if (frame.draws[d].block_rows[b] != kBlockAnyRow) continue;
    fill_block_corners<T, Indexed>(frame.scene->draws[d].indices.data(), count, b, block);
    if (block_outside(block.in)) frame.draws[d].block_rows[b] = kNoRow;
  }
  return true;
}

}  // namespace

// One block, lane by lane in primitive order, into this worker's tiles.
void BandWorker::draw_block(uint32_t d, const SmallBlock& block) {
  const SmallBlockOutput& out = block.out;
  const DrawRaster& raster = frame_.draws[d].raster;
  if (out.scalar_mask == 0 && out.job_mask == 0 && draw_grid_block(d, block, raster)) return;
  if (out.scalar_mask == 0 && draw_lanes_in_one_row(block, encode_owner(d, block.first), raster)) return;
  for (uint32_t l = 0; l < block.in.count; ++l) {
    const uint32_t bit = 1u << l;
    if (out.scalar_mask & bit)
      lane_triangle(d, block, int(l));
    else if ((out.grid_mask | out.job_mask) & bit)
      draw_small(d, block, int(l), raster);
  }
}

// Lane l through the scalar set-up (BandWorker::triangle), which draws tile by tile into this
// worker's tiles: the block's corners are assemble_primitive's positions.
void BandWorker::lane_triangle(uint32_t d, const SmallBlock& block, int lane) {
  const size_t at = size_t(lane) * block.in.stride;
  triangle(d, block.first + uint32_t(lane), block.in.corners[0][at], block.in.corners[1][at], block.in.corners[2][at]);
}

BandWorker::Reach BandWorker::row_reach(int32_t tile_y, int32_t x0, int32_t x1, int32_t lead) const {
  const uint8_t kind = row_kind_[size_t(tile_y)];
  if (kind != 2) return kind == 0 ? Reach::None : Reach::All;
  const int32_t tx0 = x0 >> kTileOrder, tx1 = x1 >> kTileOrder;
  if (owned_tiles(tile_y, tx0, tx1) == 0) return Reach::None;
  const int32_t from = std::max((x0 - lead) >> kTileOrder, 0), to = std::min(tx1, frame_.raster.tiles_x - 1);
  return owned_tiles(tile_y, from, to) == to - from + 1 ? Reach::All : Reach::Mixed;
}

BandWorker::Reach BandWorker::small_reach(int32_t x0, int32_t x1, int32_t lead, int32_t& row_lo,
                                          int32_t& row_hi) const {
  const int32_t ty0 = row_lo >> kTileOrder, ty1 = row_hi >> kTileOrder;
  const Reach r0 = row_reach(ty0, x0, x1, lead), r1 = ty1 == ty0 ? r0 : row_reach(ty1, x0, x1, lead);
  if (r0 == Reach::Mixed || r1 == Reach::Mixed) return Reach::Mixed;
  if (r0 == Reach::None && r1 == Reach::None) return Reach::None;
  if (r0 == Reach::None)
    row_lo = ty1 << kTileOrder;
  else if (r1 == Reach::None)
    row_hi = (ty1 << kTileOrder) - 1;
  return Reach::All;
}

// In a shared row the block's lanes say which tiles it may reach: an unclipped triangle's pixels
// lie within its corners' columns, a clipped one's within its pieces' rectangles (the block-row
// phase's table; one clipped in place: any column); a lane with its corners outside one plane, or
// one that failed to snap, draws nothing. The columns are the block's alone, worked out before the
// walks for every block of a shared row (the block-column phase, block_phases.cpp), so that a unit
// decides from them before it reads the block's corners (known_want); a block they were not
// worked out for (none where the phase ran) has them worked out by each unit that needs them. The
// walks only read block_columns (next_block_in_run_avx2 reads eight at a time).
BandWorker::Want BandWorker::known_want(uint32_t d, uint32_t rows, uint32_t b) const {
  if (rows == kBlockAnyRow) return Want::Yes;
  const TileRowRange r = rows_in_frame(rows, frame_.raster.tiles_y);
  if (r.lo > r.hi) return Want::No;
  if (whole_before_[size_t(r.hi) + 1] != whole_before_[size_t(r.lo)]) return Want::Yes;  // a row of its own
  // set with block_rows (the block-row phase), without which every block is kBlockAnyRow here
  const uint32_t columns = frame_.draws[d].block_columns[b];
  if (columns == kColumnsUnknown) return Want::Unknown;
  return columns_reach_own_tiles(r, columns) ? Want::Yes : Want::No;
}

bool BandWorker::wants_by_corners(uint32_t d, uint32_t rows, const SmallBlock& block) const {
  return columns_reach_own_tiles(rows_in_frame(rows, frame_.raster.tiles_y), block_tile_columns(frame_, d, block));
}

// Whether tile columns `columns` (block_tile_columns) of tile rows r hold a tile of this worker's
// in a shared row (none of those rows is all its own: known_want).
bool BandWorker::columns_reach_own_tiles(TileRowRange r, uint32_t columns) const {
  if (columns == kColumnsAny) return true;
  const int32_t x0 = int32_t(columns & 0xFFFFu) - 1, x1 = int32_t(columns >> 16) - 1;
  for (int32_t ty = r.lo; ty <= r.hi; ++ty)
    if (row_kind_[size_t(ty)] == 2 && owned_tiles(ty, x0, x1) > 0) return true;
  return false;
}

uint32_t block_tile_columns(const FastFrame& frame, uint32_t d, const SmallBlock& block) {
  const SmallBlockInput& in = block.in;
  const std::vector<ClippedEntry>& clipped = frame.draws[d].clipped;
  int32_t x0 = INT32_MAX, x1 = INT32_MIN;
  float x_min = INFINITY, x_max = -INFINITY;
  for (uint32_t l = 0; l < in.count; ++l) {
    const size_t at = size_t(l) * in.stride;
    const uint32_t fa = in.vertices[in.corners[0][at]].flags, fb = in.vertices[in.corners[1][at]].flags,
                   fc = in.vertices[in.corners[2][at]].flags;
    if (fa & fb & fc & kVertexClipBits) continue;  // ClipFate::Outside
    if ((fa | fb | fc) & kVertexClipBits) {
      const uint32_t primitive = block.first + l;
      const auto entry = std::lower_bound(clipped.begin(), clipped.end(), primitive,
                                          [](const ClippedEntry& p, uint32_t q) { return p.primitive < q; });
      if (entry == clipped.end() || entry->primitive != primitive || entry->in_place) return kColumnsAny;
      for (uint32_t k = 0; k < entry->count; ++k) {
        const PixelRect& r = entry->pieces[k].rect;
        if (r.empty()) continue;
        x0 = std::min(x0, r.x0);
        x1 = std::max(x1, r.x1);
      }
      continue;
    }
    if ((fa | fb | fc) & kVertexSnapFailed) continue;  // SetupFate::NonFinite
    for (int k = 0; k < 3; ++k) {
      const float x = in.vertices[in.corners[k][at]].x;
      x_min = std::min(x_min, x);
      x_max = std::max(x_max, x);
    }
  }
  // a snapped position lies within 2^23 px: the conversions are exact enough, with a column of margin
  if (x_min <= x_max) {
    x0 = std::min(x0, int32_t(std::floor(x_min)) - 2);
    x1 = std::max(x1, int32_t(std::ceil(x_max)) + 1);
  }
  const int32_t tiles = frame.raster.tiles_x;
  if (x0 > x1) return uint32_t(tiles + 1) | 0u << 16;  // none: x0 = tiles_x, x1 = -1
  const int32_t t0 = std::clamp(x0 >> kTileOrder, -1, tiles), t1 = std::clamp(x1 >> kTileOrder, -1, tiles);
  return uint32_t(t0 + 1) | uint32_t(t1 + 1) << 16;
}

// A block without scalar lanes whose lanes all lie in one tile row of this worker: the tiles of
// their union prepared once, then each lane drawn in order (its own rows are all this worker's);
// false when the block needs the lane-by-lane path.
bool BandWorker::draw_lanes_in_one_row(const SmallBlock& block, uint32_t owner_of_lane_0, const DrawRaster& raster) {
  const SmallBlockOutput& out = block.out;
  const uint32_t lanes = (out.grid_mask | out.job_mask) & ((1u << block.in.count) - 1u);
  if (lanes == 0) return true;
  int32_t x0 = INT32_MAX, y0 = INT32_MAX, x1 = INT32_MIN, y1 = INT32_MIN;
  for (uint32_t bits = lanes; bits != 0; bits &= bits - 1) {
    const int l = std::countr_zero(bits);
    x0 = std::min(x0, out.x0[l]), y0 = std::min(y0, out.y0[l]);
    x1 = std::max(x1, out.x1[l]), y1 = std::max(y1, out.y1[l]);
  }
  const int32_t ty = y0 >> kTileOrder;
  if (ty != (y1 >> kTileOrder)) return false;
  int32_t row_lo = y0, row_hi = y1;
  const Reach reach = small_reach(x0, x1, out.job_mask != 0 ? job_lead(raster) : 0, row_lo, row_hi);
  if (reach != Reach::All) return reach == Reach::None;  // Mixed: lane by lane
  prepare_small_tiles(x0, x1, y0, y1, raster);
  for (uint32_t bits = lanes; bits != 0; bits &= bits - 1) {
    const int l = std::countr_zero(bits);
    draw_lane(out, l, owner_of_lane_0 + uint32_t(l), out.y0[l], out.y1[l], raster);
  }
  return true;
}

// The common case of a mesh: only grid lanes, all in one tile row. The row and tile checks are
// made once for the block; false when the block needs the lane-by-lane path.
bool BandWorker::draw_grid_block(uint32_t d, const SmallBlock& block, const DrawRaster& raster) {
  const SmallBlockOutput& out = block.out;
  if (out.grid_mask == 0) return true;
  if (out.window) {
    draw_window_block(d, block, raster);
    return true;
  }
  const int32_t x0 = out.grid_x0, y0 = out.grid_y0, x1 = out.grid_x1, y1 = out.grid_y1;
  const int32_t ty = y0 >> kTileOrder;
  if (ty != (y1 >> kTileOrder)) return false;
  int32_t row_lo = y0, row_hi = y1;
  const Reach reach = small_reach(x0, x1, 0, row_lo, row_hi);
  if (reach != Reach::All) return reach == Reach::None;  // Mixed: lane by lane
  prepare_small_tiles(x0, x1, y0, y1, raster);
  raster.grid_block_fn(out, encode_owner(d, block.first), raster.kernel.write, frame_.raster.target);
  return true;
}

// A window block (small_window.hpp): its union's rows in this worker's tile rows (at most two
// tile rows: the union is at most kWindowHeight <= kTileSize rows), their tiles prepared, then the
// compositor over them. A union that crosses into another worker's tile: each lane that reaches
// this worker's tiles through the scalar set-up, in order (the block has no grid bits to scatter).
void BandWorker::draw_window_block(uint32_t d, const SmallBlock& block, const DrawRaster& raster) {
  static_assert(kWindowHeight <= kTileSize);
  const SmallBlockOutput& out = block.out;
  int32_t row_lo = out.grid_y0, row_hi = out.grid_y1;
  const Reach reach = small_reach(out.grid_x0, out.grid_x1, 0, row_lo, row_hi);
  if (reach == Reach::None) return;
  if (reach == Reach::Mixed) {
    for (uint32_t bits = out.grid_mask & ((1u << block.in.count) - 1u); bits != 0; bits &= bits - 1) {
      const int l = std::countr_zero(bits);
      int32_t lo = out.y0[l], hi = out.y1[l];
      if (small_reach(out.x0[l], out.x1[l], 0, lo, hi) != Reach::None) lane_triangle(d, block, l);
    }
    return;
  }
  prepare_small_tiles(out.grid_x0, out.grid_x1, row_lo, row_hi, raster);
  raster.window_block_fn(out, encode_owner(d, block.first), row_lo, row_hi, raster.kernel, frame_.raster.target);
}

// Before small triangles write into columns [x0, x1] of rows [row_lo, row_hi]: earlier batched
// triangles drawn first (submission order), the tiles cleared, their depth bounds unknown when
// depth is written.
void BandWorker::prepare_small_tiles(int32_t x0, int32_t x1, int32_t row_lo, int32_t row_hi, const DrawRaster& raster) {
  if (!batch_.empty()) flush(raster);
  for (int32_t ty = row_lo >> kTileOrder; ty <= row_hi >> kTileOrder; ++ty) {
    for (int32_t tx = x0 >> kTileOrder; tx <= x1 >> kTileOrder; ++tx) {
      TileState& tile = frame_.raster.tile(tx, ty);
      if (!tile.cleared) clear_tile_row(ty, index_, frame_.raster);
      if (raster.depth.write) tile.bounds.state = BoundsState::Unknown;  // before any write lands
    }
  }
}

// A small triangle: a grid lane (which may reach into a neighbouring tile row or column: only
// this worker's rows are written) or a kernel job (the same). Its tiles are cleared first;
// their depth bounds become unknown when depth is written. A lane that reaches another worker's
// tile in a shared row takes the scalar set-up, which draws tile by tile.
void BandWorker::draw_small(uint32_t d, const SmallBlock& block, int lane, const DrawRaster& raster) {
  const SmallBlockOutput& out = block.out;
  int32_t row_lo = out.y0[lane], row_hi = out.y1[lane];  // a lane spans at most two tile rows
  const bool job = (out.job_mask >> lane) & 1u;
  const Reach reach = small_reach(out.x0[lane], out.x1[lane], job ? job_lead(raster) : 0, row_lo, row_hi);
  if (reach == Reach::None) return;
  if (reach == Reach::Mixed) {
    if (job && raster.small_piece_fn != nullptr) return draw_job_pieces(d, block, lane, raster);
    return lane_triangle(d, block, lane);
  }
  prepare_small_tiles(out.x0[lane], out.x1[lane], row_lo, row_hi, raster);
  draw_lane(out, lane, encode_owner(d, block.first + uint32_t(lane)), row_lo, row_hi, raster);
}

// A kernel job lane that crosses into another worker's tile, where the kernel writes nothing
// outside its rectangle (small_piece_fn): the lane's rectangle cut to each of this worker's
// tiles, each piece's tile prepared and drawn. A lane covers each pixel once, so drawing it piece
// by piece writes what one call over its rectangle would; the next lane comes after the last piece.
void BandWorker::draw_job_pieces(uint32_t d, const SmallBlock& block, int lane, const DrawRaster& raster) {
  const SmallBlockOutput& out = block.out;
  const uint32_t owner = encode_owner(d, block.first + uint32_t(lane));
  const int32_t x0 = out.x0[lane], y0 = out.y0[lane], x1 = out.x1[lane], y1 = out.y1[lane];
  const int32_t ty_hi = std::min(y1 >> kTileOrder, frame_.raster.tiles_y - 1);
  const int32_t tx_hi = std::min(x1 >> kTileOrder, frame_.raster.tiles_x - 1);
  for (int32_t ty = std::max(y0 >> kTileOrder, 0); ty <= ty_hi; ++ty) {
    for (int32_t tx = std::max(x0 >> kTileOrder, 0); tx <= tx_hi; ++tx) {
      if (!owns_tile(tx, ty)) continue;
      const PixelRect piece{std::max(x0, tx * kTileSize), std::max(y0, ty * kTileSize),
                            std::min(x1, tx * kTileSize + kTileSize - 1), std::min(y1, ty * kTileSize + kTileSize - 1)};
      prepare_small_tiles(piece.x0, piece.x1, piece.y0, piece.y1, raster);
      raster.small_piece_fn(out, lane, owner, piece, raster.kernel, frame_.raster.target);
    }
  }
}

// A grid lane or a kernel job in rows [row_lo, row_hi], its tiles prepared.
void BandWorker::draw_lane(const SmallBlockOutput& block, int lane, uint32_t owner, int32_t row_lo, int32_t row_hi,
                           const DrawRaster& raster) {
  if ((block.grid_mask >> lane) & 1u)
    raster.grid_fn(block, lane, owner, row_lo, row_hi, raster.kernel.write, frame_.raster.target);
  else
    raster.small_fn(block, lane, owner, row_lo, row_hi, raster.kernel, frame_.raster.target);
}

namespace {

template <Topology T, bool Indexed>
void measure_columns(FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end,
                     const std::vector<uint32_t>& shared_before) {
  const uint32_t* block_rows = frame.draws[d].block_rows;
  uint32_t* block_columns = frame.draws[d].block_columns;
  const uint32_t count = primitive_count(frame.scene->draws[d]);
  SmallBlock block;
  fill_block_draw(frame, d, block);
  for (uint32_t b = begin; b < end; ++b) {
    const uint32_t rows = block_rows[b];
    if (rows == kBlockAnyRow) continue;  // every unit that meets it sets it up (known_want)
    const TileRowRange r = rows_in_frame(rows, frame.raster.tiles_y);
    if (r.lo > r.hi || shared_before[size_t(r.hi) + 1] == shared_before[size_t(r.lo)]) continue;
    fill_block_corners<T, Indexed>(frame.scene->draws[d].indices.data(), count, b, block);
    block_columns[b] = block_tile_columns(frame, d, block);
  }
}

}  // namespace

void measure_block_columns(FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end,
                           const std::vector<uint32_t>& shared_before) {
  on_triangle_layout(
      frame.scene->draws[d],
      [&](auto topology, auto indexed) { measure_columns<topology(), indexed()>(frame, d, begin, end, shared_before); },
      [] {});
}

bool measure_block_rows(FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end) {
  return on_triangle_layout(
      frame.scene->draws[d],
      [&](auto topology, auto indexed) { return measure_rows<topology(), indexed()>(frame, d, begin, end); },
      [] { return true; });
}

}  // namespace rastercmp::cpu::fast
