// Which worker draws each tile: an estimate of each tile row's work, then a greedy assignment of
// whole rows, or of runs of a row's tiles where one row holds more than a worker's share. Any
// assignment gives the same bytes (each tile is drawn by exactly one worker, in submission order);
// the estimate only decides how evenly the band phase splits.
#pragma once

#include <cstdint>
#include <vector>

namespace rastercmp::cpu::fast {

// The estimate of a tile row's work, in units of about 1,500 instructions (callgrind, Zen 5,
// AVX-512 kernels; perspective at 1024x1024; docs/performance-log.md, d4a504f): each block of eight small triangles that
// reaches the row costs about 8 (its set-up and drawing there: 12,000 instructions);
// each tile of the row about 4 for its clear, and more where any block reaches the row (a
// reached row is mostly a covered row: perspective's near tile rows hold 1-6 blocks of big
// triangles each and cost about 1M instructions to fill; 40 before 134c834). The weights move
// with the paths' costs: 30c5ae9 to 77da606 tried 4 and 6 as its changes shifted work between blocks and
// filled tiles, and at its end perspective's two workers split 426/430 us with 8 (7 and 9 alike),
// 438/394 with 6.
// 134c834 (blocks with clipped lanes counted in their rows) measured each of perspective's
// rows alone: its near rows (a few big triangles' blocks each) cost 46-54 us, its horizon row (818
// blocks of tiny triangles) 184 us. A filled tile now weighs 100: after a lavapipe render the two
// workers split 532/498 us, against 467/587 with 40 (and 0.75-0.76 ms against 0.79-0.80 a render).
inline constexpr uint64_t kRowWeightPerBlock = 8;
inline constexpr uint64_t kRowWeightPerClearedTile = 4;
inline constexpr uint64_t kRowWeightPerFilledTile = 100;
uint64_t tile_row_weight(uint64_t blocks, uint32_t tiles_x);

// worker[r] for every row: rows by weight, heaviest first (ties: lower row first), each to the
// worker that would finish it first, (load + weight) / speed (ties: lower worker): with equal
// speeds (none given, or all 1) the least-loaded worker so far. `speeds` (WorkerPool::
// relative_speeds): one per worker, in (0, 1]. Deterministic; every row gets exactly one of
// 0..workers-1. workers >= 1.
std::vector<uint32_t> balance_rows(const std::vector<uint64_t>& weights, uint32_t workers,
                                   const std::vector<double>& speeds = {});

// How the band phase shares out the tiles (weights.size() rows of tiles_x tiles, row-major). When
// no row weighs more than kCutShareNum / kCutShareDen of a worker's share (the total / workers;
// cuts_rows): whole rows, unit[t] the worker that draws tile t (balance_rows), count = workers.
// Otherwise (perspective's horizon row held two fifths of its work: one worker's whole at 16) the
// rows are cut into pieces: a row over the share is cut into k = ceil(kPiecesPerShare * weight /
// share) runs of whole tiles (at most tiles_x), each taken to weigh its part of the row by its
// tiles, every other row one piece; unit[t] is then the piece's place among them by weight,
// heaviest first (ties: lower row, then left piece first), and the workers take the pieces from a
// queue in that order (queued): the estimate knows rows, not columns, and a queue evens out what it
// gets wrong. Deterministic.
inline constexpr uint64_t kPiecesPerShare = 2;
// Cut only where a row outweighs the share by more than a quarter: cut rows cost more than their
// weight (the block-column phase, each unit's walk of the draws), and whole rows leave a worker at
// most the heaviest row. tiny_1m at 16 workers, its rows 0.99-1.13 shares each, was cut into 38
// units: bands projected 1.60 ms and block columns 0.23 (92,000 blocks), where whole rows project
// 1.30-1.59 ms in all (docs/performance-log.md, "Perspective at 16 workers ...").
inline constexpr uint64_t kCutShareNum = 5, kCutShareDen = 4;
// Whether balance_tiles cuts rows into queued units: some row weighs more than kCutShareNum /
// kCutShareDen of a worker's share.
bool cuts_rows(const std::vector<uint64_t>& weights, uint32_t tiles_x, uint32_t workers);
struct TileUnits {
  std::vector<uint32_t> unit;  // per tile
  uint32_t count = 0;          // units
  bool queued = false;
  bool operator==(const TileUnits&) const = default;
};
// `speeds` as for balance_rows, for whole rows (queued pieces need none).
TileUnits balance_tiles(const std::vector<uint64_t>& weights, uint32_t tiles_x, uint32_t workers,
                        const std::vector<double>& speeds = {});

// Which of `workers` runs of consecutive rows each of `rows` rows belongs to, the runs' lengths in
// proportion to `speeds` (as for balance_rows): row r to worker r * workers / rows when they are
// equal (none given, or all 1). Every worker's run is consecutive and they follow in order.
std::vector<uint32_t> contiguous_runs(uint32_t rows, uint32_t workers, const std::vector<double>& speeds = {});

}  // namespace rastercmp::cpu::fast
