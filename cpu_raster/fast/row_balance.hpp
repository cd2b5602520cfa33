// Which worker draws each tile row (issue #23): an estimate of each row's work, then a greedy
// assignment of whole rows. Any assignment gives the same bytes (each row is drawn by exactly one
// worker, in submission order); the estimate only decides how evenly the band phase splits.
#pragma once

#include <cstdint>
#include <vector>

namespace rastercmp::cpu::fast {

// The estimate of a tile row's work, in units of about 1,500 instructions (callgrind, Zen 5,
// AVX-512 kernels; perspective at 1024x1024, session 12): each block of eight small triangles that
// reaches the row costs about 4 (session 12 measured 8, 12,000 instructions; session 15's kernel
// jobs for lanes up to 32x16 px and whole-row clears halved it against the filled tiles: at 2
// workers perspective took 0.72-0.73 ms with 4, 0.74-0.75 with 3 or 6, 0.80-0.82 with 8); each tile
// of the row about 4 for its clear, and about 40 more where any block reaches the row (a reached
// row is mostly a covered row: perspective's near tile rows hold 1-6 blocks of big triangles each
// and cost about 1M instructions to fill).
inline constexpr uint64_t kRowWeightPerBlock = 4;
inline constexpr uint64_t kRowWeightPerClearedTile = 4;
inline constexpr uint64_t kRowWeightPerFilledTile = 40;
uint64_t tile_row_weight(uint64_t blocks, uint32_t tiles_x);

// worker[r] for every row: rows by weight, heaviest first (ties: lower row first), each to the
// least-loaded worker so far (ties: lower worker). Deterministic; every row gets exactly one of
// 0..workers-1. workers >= 1.
std::vector<uint32_t> balance_rows(const std::vector<uint64_t>& weights, uint32_t workers);

}  // namespace rastercmp::cpu::fast
