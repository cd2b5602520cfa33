// Which tile rows a block of eight small triangles may reach (the block-row phase, block_phases.cpp
// phase 3): from its corners' tile rows (fast_vertices.hpp), packed lo | hi << 16 and cut to the
// draw region's rows (lo > hi: none), or kBlockAnyRow.
#pragma once

#include <algorithm>
#include <cstdint>

#include "cpu_raster/fast/small_triangles.hpp"

namespace rastercmp::cpu::fast {

// Tile rows lo..hi cut to the draw region's, packed; kNoRow (lo > hi) when none is left.
inline constexpr uint32_t kNoRow = 0xFFFFu;
uint32_t pack_rows(int32_t lo, int32_t hi, const PixelRect& region);

// Packed rows (not kBlockAnyRow) unpacked and cut to the frame's tile rows [0, tiles_y - 1];
// lo > hi: none.
struct TileRowRange {
  int32_t lo, hi;
};
inline TileRowRange rows_in_frame(uint32_t rows, int32_t tiles_y) {
  return {std::max(int32_t(rows & 0xFFFFu), 0), std::min(int32_t(rows >> 16), tiles_y - 1)};
}

// Any block: kBlockAnyRow when a corner needs clipping or failed to snap (its window position
// says nothing then), or names no position (`bad` is set then).
uint32_t block_tile_rows(const SmallBlockInput& in, const int16_t* tile_rows, uint32_t positions,
                         const PixelRect& region, bool& bad);

// AVX2 hosts only: the same for a full block of an indexed list (24 consecutive indices), except
// that a block whose every lane has its three corners outside one clip plane (the set-up drops
// such lanes: ClipFate::Outside) gets kNoRow: nobody sets it up. tile_rows is readable 2 bytes
// past its last position (thread_row_scratch).
uint32_t list_block_tile_rows_avx2(const uint32_t* indices, const int16_t* tile_rows, uint32_t positions,
                                   const PixelRect& region, bool& bad);

// AVX2 hosts only: the rows of n full blocks of an indexed list (24 * n consecutive indices) at
// once, written to block_rows[0..n), when that is cheap and gives every block exactly what
// list_block_tile_rows_avx2 gives it; false (nothing written) otherwise, and when an index is out
// of range. At most kSpanBlocks blocks, at most kSpanPositions positions read.
inline constexpr uint32_t kSpanBlocks = 16;
inline constexpr uint32_t kSpanPositions = 4096;
bool span_tile_rows_avx2(const uint32_t* indices, uint32_t n, const int16_t* tile_rows, uint32_t positions,
                         const PixelRect& region, uint32_t* block_rows);

// AVX2 hosts only: the first b in [begin, end) whose block_rows[b] is not kNoRow (a block some
// worker sets up), or end. The walks skip a camera's blocks behind or beside it eight at a time
// (perspective: 8,911 of its 10,000 blocks).
uint32_t next_reaching_block_avx2(const uint32_t* block_rows, uint32_t begin, uint32_t end);

// AVX2 hosts only: the first b in [begin, end) that a unit drawing tile columns [first, last] of
// tile row tile_y alone may set up: block_rows[b] kBlockAnyRow, or rows that hold tile_y with
// block_columns[b] (packed as block_tile_columns packs them) kColumnsAny, kColumnsUnknown or
// meeting [first, last]; end if none. Every block BandWorker::known_want does not answer No for
// such a unit is one (it may answer No for one of them); the walks of perspective's horizon units
// skip the blocks of the other units' columns eight at a time.
uint32_t next_block_in_run_avx2(const uint32_t* block_rows, const uint32_t* block_columns, uint32_t begin,
                                uint32_t end, int32_t tile_y, int32_t first, int32_t last);

}  // namespace rastercmp::cpu::fast
