// Phases 3 and 3b of a fast render with several workers (render_fast.cpp): which tile rows each
// block of 8 small triangles may reach (the block-row phase, with the trailing runs' denormal
// checks and the clipped triangles; with few row tasks a worker, a clip phase after it), the row
// balance from those rows, and, where a tile row is shared between queued units, the tile columns
// of the blocks that reach it (the block-column phase).
#pragma once

#include <cstdint>
#include <vector>

#include "cpu_raster/fast/fast_frame.hpp"

namespace rastercmp::cpu::fast {

// A draw's trailing pipelined run [first, primitive count) whose set-ups the block-row phase
// checks for denormals (run_meets_denormals), a range of primitives per task.
struct TrailingCheck {
  uint32_t draw, first;
};

// The index scans the profile check left out, for the draws the block-row phase does not read
// whole (it checks the indices it reads). A bad index: the full check, which throws the error it
// would have thrown first.
void check_index_ranges(const FastFrame& frame);

// Phase 3 (with its clip phase): the blocks' tile rows, the trailing runs' checks (`checks`,
// from the vertex phase), the clipped triangles' table, and the tiles' workers.
void measure_all_block_rows(FastFrame& frame, const std::vector<TrailingCheck>& checks);

// Phase 3b: the tile columns of the blocks that reach a tile row shared between queued units.
void measure_shared_columns(FastFrame& frame);

}  // namespace rastercmp::cpu::fast
