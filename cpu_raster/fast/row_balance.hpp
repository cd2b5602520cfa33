// Which worker draws each tile row (issue #23): an estimate of each row's work, then a greedy
// assignment of whole rows. Any assignment gives the same bytes (each row is drawn by exactly one
// worker, in submission order); the estimate only decides how evenly the band phase splits.
#pragma once

#include <cstdint>
#include <vector>

namespace rastercmp::cpu::fast {

// The estimate of a tile row's work, in units of about 1,500 instructions (callgrind, Zen 5,
// AVX-512 kernels; perspective at 1024x1024, session 12): each block of eight small triangles that
// reaches the row costs about 6 (session 12 measured 8, 12,000 instructions; session 15's
// whole-row clears and kernel jobs for lanes up to 64x32 px moved work between the terms, and at 2
// workers perspective was fastest with 6: 0.555 ms against 0.581 with 4, 0.559 with 8, 0.618 with
// 12, and 0.667-0.676 against 0.691-0.694 with 8 in a slower hour of the host); each tile of the row
// about 4 for its clear, and about 40 more where any block reaches the row (a reached row is mostly
// a covered row: perspective's near tile rows hold 1-6 blocks of big triangles each and cost about
// 1M instructions to fill).
inline constexpr uint64_t kRowWeightPerBlock = 6;
inline constexpr uint64_t kRowWeightPerClearedTile = 4;
inline constexpr uint64_t kRowWeightPerFilledTile = 40;
uint64_t tile_row_weight(uint64_t blocks, uint32_t tiles_x);

// worker[r] for every row: rows by weight, heaviest first (ties: lower row first), each to the
// least-loaded worker so far (ties: lower worker). Deterministic; every row gets exactly one of
// 0..workers-1. workers >= 1.
std::vector<uint32_t> balance_rows(const std::vector<uint64_t>& weights, uint32_t workers);

}  // namespace rastercmp::cpu::fast
