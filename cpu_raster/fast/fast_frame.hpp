// Everything a fast render shares between its phases and workers (render_fast.cpp):
// the exact path's frame context and targets, the per-draw vertex arrays and raster state, and
// the tiles' depth bounds.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <vector>

#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/render_targets.hpp"
#include "cpu_raster/fast/fast_vertices.hpp"
#include "cpu_raster/fast/render_fast.hpp"
#include "cpu_raster/fast/tile_raster.hpp"

namespace rastercmp::cpu::fast {

// The pieces of one clipped triangle (clipped_pieces.hpp) in its ClippedTable.
struct ClippedPrimitive {
  uint32_t primitive = 0;
  uint32_t first = 0, count = 0;  // ClippedTable::pieces[first, first + count)
  bool in_place = false;          // a piece takes llvmpipe's wrapping set-up: the walk clips it itself
};

// The clipped triangles one task of the block-row or clip phase set up, in primitive order
// (clipped_pieces.hpp).
struct ClippedTable {
  std::vector<ClippedPrimitive> primitives;
  std::vector<FastTriangle> pieces;  // rectangles cut to the draw region (maybe empty)
};

// A clipped triangle of a draw with its pieces where its task's table holds them
// (FastFrame::clipped_tables): the tables are indexed, not copied together.
struct ClippedEntry {
  uint32_t primitive = 0, count = 0;
  const FastTriangle* pieces = nullptr;  // [pieces, pieces + count)
  bool in_place = false;                 // ClippedPrimitive::in_place
};

struct FastDraw {
  // Triangles of a single-sample frame take the fast walk; anything else (lines, 4x) the exact
  // front end and rasterizer, restricted to each worker's rows.
  bool fast = false;
  FastVertex* vertices = nullptr;  // fast draws: one per position (VertexScratch)
  int16_t* tile_rows = nullptr;    // fast draws: per position, its tile row or kRowUnknown
  // docs/lavapipe-rules.md §1.5: per driver chunk (draw_chunks.hpp), whether it takes the pipeline path;
  // empty when no position of the draw is outside the clip volume, or when culling is off (the
  // pipeline path's float cull is then all that would differ, and it drops nothing).
  std::vector<bool> pipelined_chunks;
  uint32_t chunk_size = 1;  // primitives per chunk
  bool pipelined(uint32_t primitive) const {
    return !pipelined_chunks.empty() && pipelined_chunks[primitive / chunk_size];
  }
  bool any_pipelined() const {
    return std::find(pipelined_chunks.begin(), pipelined_chunks.end(), true) != pipelined_chunks.end();
  }
  SetupContext setup;  // for the exact set-up of clipped triangles
  DrawRaster raster;
  bool small_blocks = false;       // set up eight triangles at a time (small_triangles.hpp)
  uint32_t* block_rows = nullptr;  // per block of 8: the tile rows it may reach (band_worker.cpp)
  // Per block of 8 (with block_rows): the tile columns its lanes may reach in a shared row, worked
  // out by the block-column phase for the blocks of shared rows (block_phases.cpp);
  // kColumnsUnknown for the others. Read only by the walks.
  uint32_t* block_columns = nullptr;
  // Per group of kGroupBlocks blocks (with block_rows): the rows its blocks reach, packed as
  // block_rows (the least lo and the greatest hi; kNoRow: none; kBlockAnyRow: one may reach any).
  // A walk skips a group that reaches none of its worker's rows.
  uint32_t* group_rows = nullptr;
  // several workers: its clipped triangles, set up once, sorted by primitive
  std::vector<ClippedEntry> clipped;
  // Several workers, a line or triangle list the exact front end walks: per primitive, the tile
  // rows it may reach (exact_reach.hpp's packed form), from the reach phase; null elsewhere.
  uint32_t* list_reach = nullptr;
};

// block_rows value of a block that must be set up by every worker.
inline constexpr uint32_t kBlockAnyRow = 0xFFFFFFFFu;
// block_columns values: not worked out yet; any column (a lane clipped in place).
inline constexpr uint32_t kColumnsUnknown = 0xFFFFFFFFu;
inline constexpr uint32_t kColumnsAny = 0xFFFFFFFEu;
// Blocks per group_rows entry.
inline constexpr uint32_t kGroupBlocks = 64;

// TileState::worker of the tiles of a row no worker (or unit) owns (FastFrame::unowned_rows).
inline constexpr uint32_t kUnownedRow = 0xFFFFFFFFu;

struct FastFrame {
  const Scene* scene = nullptr;
  FrameContext exact;     // cpu::make_frame_context: viewport, region, methods
  RenderTargets targets;  // the attachments, written in place (cleared tile by tile)
  // Where targets.width, their row pitch, is wider than the frame (frame_row_pitch): the result's
  // attachments at the frame's width, into which each worker copies its tiles when its walk is
  // done (BandWorker::pack_tile_row); null otherwise.
  uint32_t* packed_owner = nullptr;
  uint32_t* packed_depth = nullptr;
  FrameRaster raster;     // pointers into targets, tiles, dispatch
  std::vector<TileState> tiles;
  std::vector<FastDraw> draws;
  std::vector<ClippedTable> clipped_tables;  // the pieces FastDraw::clipped points into
  uint32_t workers = 1;  // each tile drawn by one of them: TileState::worker (row_balance.hpp)
  // 0: TileState::worker is the worker that draws the tile. Otherwise the tiles are in this many
  // units, TileState::worker the unit, which the workers take from a queue (render_fast.cpp).
  uint32_t queued_units = 0;
  // The tile rows nothing draws into (block_phases.cpp, balance_tile_rows): no worker owns them;
  // each worker, its walk done, clears the next one not taken yet, so the first to finish clears
  // more of them (a camera's sky: six of perspective's sixteen rows).
  std::vector<int32_t> unowned_rows;
  std::atomic<size_t> next_unowned{0};
  // Without queued units, each worker's rows' estimated work (row_balance.hpp), which the band
  // phase's pace is measured against (WorkerPool::record_pace); empty: not measured.
  std::vector<double> worker_work;
  RenderProfile* profile = nullptr;  // FastConfig::profile
  uint32_t profile_threads = 0;      // FastConfig::profile_threads
  double serial_mark = 0;            // profiled: the calling thread's CPU time when its last phase ended
  // The first primitive, in submission order, whose clipping or set-up threw in a worker's walk of
  // the exact draws (BandWorker::walk_exact), and what it threw: rethrown after the band phase,
  // whichever worker met it first in time, so that the error is the exact path's.
  struct Failure {
    uint32_t draw = UINT32_MAX, primitive = UINT32_MAX;
    std::exception_ptr error;
  };
  std::mutex failure_mutex;
  Failure failure;
  void record_failure(uint32_t draw, uint32_t primitive, std::exception_ptr error) {
    const std::lock_guard<std::mutex> lock(failure_mutex);
    if (draw < failure.draw || (draw == failure.draw && primitive < failure.primitive))
      failure = Failure{draw, primitive, std::move(error)};
  }
};

}  // namespace rastercmp::cpu::fast
