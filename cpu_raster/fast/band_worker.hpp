// One worker of a fast render: it walks every draw in submission order and rasterizes into the
// tiles it owns (TileState::worker: whole tile rows, or runs of a heavy row's tiles), so each pixel
// sees its primitives in order, whatever the number of threads (docs/lavapipe-rules.md §2.7:
// deterministic by construction).
// Per primitive: assemble → clip-mask test (clipped triangles go through the exact path's clipper
// and set-up) → rows test → fixed-point area, cull, swap → depth plane → tiles. Triangles the
// scalar set-up takes are collected (up to kBatchSize, until a small triangle comes) and drawn
// tile by tile, so that a tile stays in cache while all of them are drawn into it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cpu_raster/exact/clip_vertex.hpp"
#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/fast/block_rows.hpp"
#include "cpu_raster/fast/exact_reach.hpp"
#include "cpu_raster/fast/fast_frame.hpp"
#include "cpu_raster/fast/lean_setup.hpp"
#include "cpu_raster/fast/small_triangles.hpp"

namespace rastercmp::cpu::fast {

// Fills frame.draws[d].block_rows[begin, end) (the workers share the blocks out before the walk:
// each block is measured once, by one of them). False when a corner of these blocks names no
// position: the draw's index range is checked here, where its indices are read anyway.
bool measure_block_rows(FastFrame& frame, uint32_t draw_index, uint32_t begin, uint32_t end);

// The tile columns [x0, x1] a block's lanes may reach in a shared row (BandWorker::known_want),
// clamped to [-1, tiles_x] and packed (x0 + 1) | (x1 + 1) << 16; x0 > x1: none; kColumnsAny: a
// lane clipped in place.
uint32_t block_tile_columns(const FastFrame& frame, uint32_t draw_index, const SmallBlock& block);

// Fills frame.draws[d].block_columns[b] for each block b in [begin, end) whose block rows meet a
// shared tile row (one whose tiles more than one unit draws): shared_before[r], the shared rows
// below r, for r up to tiles_y. The others keep kColumnsUnknown.
void measure_block_columns(FastFrame& frame, uint32_t draw_index, uint32_t begin, uint32_t end,
                           const std::vector<uint32_t>& shared_before);

class BandWorker {
 public:
  // index: the worker, or with FastFrame::queued_units the unit, whose tiles (TileState::worker) it draws.
  BandWorker(FastFrame& frame, uint32_t index);
  void run();

  static constexpr size_t kBatchSize = 64;

 private:
  // Some tile of the row is this worker's.
  bool owns_tile_row(int32_t tile_y) const {
    return owned_before_[size_t(tile_y) + 1] != owned_before_[size_t(tile_y)];
  }
  bool owns_tile_rows(int32_t tile_y0, int32_t tile_y1) const;
  // Some tile of the pixel rectangle is this worker's.
  bool owns_rect(int32_t x0, int32_t y0, int32_t x1, int32_t y1) const;
  bool owns_tile(int32_t tile_x, int32_t tile_y) const { return frame_.raster.tile(tile_x, tile_y).worker == index_; }
  // How many of tile row tile_y's tiles [tile_x0, tile_x1] (cut to the frame) are this worker's.
  int32_t owned_tiles(int32_t tile_y, int32_t tile_x0, int32_t tile_x1) const;
  // Where a small triangle's writes to columns [x0, x1] of rows [row_lo, row_hi] (at most two tile
  // rows) may go, for this worker: None (no tile of it is this worker's), All (rows cut to those
  // whose tiles from x0 - lead to x1 are all this worker's), or Mixed (they cross into another
  // worker's tile: the scalar set-up, tile by tile, draws it, or for a kernel job on AVX-512 hosts
  // its pieces in this worker's tiles: draw_job_pieces). lead: the columns left of x0 that its
  // kernel may load and store back (job_lead: kJobLead for an AVX2 kernel job, whose spans may
  // start up to 7 columns left of x0 and end in x1's tile; 0 for grid lanes and windows, written
  // pixel by pixel or by masked stores, and for AVX-512 kernel jobs, masked to their rectangle).
  enum class Reach { None, All, Mixed };
  static constexpr int32_t kJobLead = 7;
  // A kernel job's lead with this draw's small kernel: none where it writes nothing outside the
  // job's rectangle (the AVX-512 kernel, which also draws pieces: small_piece_fn).
  static int32_t job_lead(const DrawRaster& raster) { return raster.small_piece_fn != nullptr ? 0 : kJobLead; }
  Reach small_reach(int32_t x0, int32_t x1, int32_t lead, int32_t& row_lo, int32_t& row_hi) const;
  Reach row_reach(int32_t tile_y, int32_t x0, int32_t x1, int32_t lead) const;
  // Whether this worker sets up block b of draw d, whose block rows are `rows` (block_rows.hpp)
  // and reach its rows: whether it may reach one of its tiles (in a shared row: by its lanes'
  // columns), before its corners are read; Unknown where its columns are not worked out (the
  // block-column phase works out those of every block that reaches a shared row).
  // wants_by_corners answers then, from the block's corners filled in.
  enum class Want { Yes, No, Unknown };
  Want known_want(uint32_t d, uint32_t rows, uint32_t b) const;
  bool wants_by_corners(uint32_t d, uint32_t rows, const SmallBlock& block) const;
  bool columns_reach_own_tiles(TileRowRange rows, uint32_t columns) const;

  template <Topology T, bool Indexed>
  void walk_triangles(uint32_t draw_index);
  void walk_fast(uint32_t draw_index);
  // The exact draws (band_worker_exact.cpp): walk_exact to raster_exact_in_band.
  bool walk_exact(uint32_t draw_index);  // false: a primitive threw (FastFrame::failure)
  DrawWalk begin_draw_transformed(uint32_t draw_index) const;
  LeanSetup setup_line_lean_flushed(bool flushed, const std::array<WindowVertex, 2>& window, uint32_t owner,
                                    const SetupContext& ctx);
  LineSetup setup_line_flushed(SetupDenormals mode, const std::array<WindowVertex, 2>& window, uint32_t owner,
                               const SetupContext& ctx, uint32_t primitive_index, bool bias_denormal);
  bool misses_own_rows(const WindowVertex* window, const uint32_t* clip_bits, uint32_t count, float margin,
                       bool may_throw) const;
  bool clipped_line_misses_own_rows(const std::array<WindowVertex, 2>& window, float margin, bool may_throw) const;
  bool span_misses_own_rows(const RowSpan& span, bool may_throw) const;
  // Where a primitive's visit may reach (misses_own_rows): not settled by its vertices, some of this
  // worker's rows, only other workers' rows, or no row of the frame.
  enum class RowReach { Unsettled, OwnRows, OtherRows, NoFrameRow };
  RowReach reach_of(const RowSpan& span) const;
  RowReach reach_of_tile_rows(uint32_t packed) const;
  RowReach reach_of_tiles(int32_t lo, int32_t hi) const;
  // The exact rasterizer for one primitive, on this worker's tile rows.
  void raster_exact_in_band(const RasterPrimitive& primitive, const DepthTestState& depth);

  template <Topology T, bool Indexed>
  void walk_small_blocks(uint32_t draw_index);
  void draw_block(uint32_t draw_index, const SmallBlock& block);
  bool draw_grid_block(uint32_t draw_index, const SmallBlock& block, const DrawRaster& raster);
  bool draw_lanes_in_one_row(const SmallBlock& block, uint32_t owner_of_lane_0, const DrawRaster& raster);
  void draw_window_block(uint32_t draw_index, const SmallBlock& block, const DrawRaster& raster);
  void draw_small(uint32_t draw_index, const SmallBlock& block, int lane, const DrawRaster& raster);
  void draw_lane(const SmallBlockOutput& block, int lane, uint32_t owner, int32_t row_lo, int32_t row_hi,
                 const DrawRaster& raster);
  void lane_triangle(uint32_t draw_index, const SmallBlock& block, int lane);
  void draw_job_pieces(uint32_t draw_index, const SmallBlock& block, int lane, const DrawRaster& raster);
  void prepare_small_tiles(int32_t x0, int32_t x1, int32_t row_lo, int32_t row_hi, const DrawRaster& raster);
  void triangle(uint32_t draw_index, uint32_t primitive, uint32_t a, uint32_t b, uint32_t c);
  void clipped_triangle(uint32_t draw_index, uint32_t primitive, uint32_t a, uint32_t b, uint32_t c);

  // The depth bounds' audit of the draw being flushed. The bounds (tile_depth_bounds.hpp) pay
  // when they leave jobs out (AllFail), tests out (AllPass) or batch triangles out
  // (first_visible), and cost a range per job and tile scans whether they pay or not: on
  // perspective's back-to-front terrain they helped 77 jobs of 8,314 and cost 6%. Once a draw
  // has consulted them kAuditCalls times with fewer than one help in kAuditRatio, this worker
  // stops consulting them for the rest of the draw (its later writes leave their tiles'
  // bounds unknown, as any write without a range does). Speed only: the bounds choose between
  // paths that write the same bytes.
  static constexpr uint32_t kAuditCalls = 64, kAuditRatio = 32;
  struct BoundsAudit {
    const DrawRaster* draw = nullptr;  // the draw counted (FastDraw::raster)
    uint32_t consulted = 0, helped = 0;
    bool off = false;
    DrawRaster without;  // the draw's raster with the bounds off, once off
  };
  const DrawRaster& audited(const DrawRaster& raster);
  void count_bounds(BoundsUse use);

  void submit(const FastTriangle& t, const DrawRaster& raster);
  void flush(const DrawRaster& raster);
  void bin_batch(int32_t tx0, int32_t ty0, int32_t tx1, int32_t ty1);
  bool may_hide(const PixelRect& tile, const uint8_t* list, size_t count, const DrawRaster& raster) const;
  size_t first_visible(const PixelRect& tile, const uint8_t* list, size_t count, const DrawRaster& raster);
  void prepare_tiles(const PixelRect& r, bool depth_write);
  void pack_tile_row(int32_t tile_y, uint32_t worker);

  FastFrame& frame_;
  uint32_t index_;  // the worker, or the queued unit (FastFrame::queued_units), whose tiles it draws
  std::vector<FastTriangle> batch_;
  std::vector<TileTriangle> prepared_;  // flush: the batch's triangles in the current tile
  // flush: per tile of the batch's union (row-major, this worker's tiles), the batch's triangles
  // whose rectangle reaches it, in submission order: tile k's are bin_list_[bin_first_[k],
  // bin_first_[k + 1]).
  std::vector<uint32_t> bin_first_;
  std::vector<uint8_t> bin_list_;
  std::vector<uint32_t> bin_next_;  // bin_batch's fill positions
  std::vector<size_t> clipped_next_;  // per draw: the first entry of its ClippedTable not yet walked past
  // Per r <= tiles_y: how many tile rows below r hold a tile of this worker's (row r holds one when
  // the count grows from r to r + 1).
  std::vector<uint32_t> owned_before_;
  // Per tile row: this worker owns every tile of it (1), some (2), none (0). shared_ is whether any
  // row is 2; whole_before_ counts the rows of 1 below r, as owned_before_.
  std::vector<uint8_t> row_kind_;
  RasterPrimitive lean_;  // walk_exact: the triangle or line the lean set-ups (lean_setup.hpp) set up last
  std::vector<uint32_t> whole_before_;
  bool shared_ = false;
  // Per tile row: the first and last of its tiles this worker owns (first > last: none). Where
  // they are all it owns between them (a unit's run of tiles, or whole rows: every assignment
  // row_balance.hpp makes), owned_tiles counts from them; otherwise (`runs_` false) tile by tile.
  std::vector<int32_t> owned_first_, owned_last_;
  bool runs_ = true;
  // A unit that draws a run of tiles of one shared row and nothing else (every queued unit of a
  // row cut into pieces, row_balance.hpp): that row; -1 otherwise. Its walks skip the blocks of
  // other columns eight at a time (next_block_in_run_avx2).
  int32_t run_row_ = -1;
  SmallBlock block_, next_block_;       // the small-triangle blocks being set up and drawn
  BoundsAudit audit_;
};

}  // namespace rastercmp::cpu::fast
