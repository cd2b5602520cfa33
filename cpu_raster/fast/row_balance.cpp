#include "cpu_raster/fast/row_balance.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>

namespace rastercmp::cpu::fast {

uint64_t tile_row_weight(uint64_t blocks, uint32_t tiles_x) {
  return blocks * kRowWeightPerBlock +
         uint64_t(tiles_x) * (kRowWeightPerClearedTile + (blocks > 0 ? kRowWeightPerFilledTile : 0));
}

namespace {

bool equal_speeds(const std::vector<double>& speeds, uint32_t workers) {
  return speeds.size() != workers || std::all_of(speeds.begin(), speeds.end(), [](double s) { return s == 1.0; });
}

}  // namespace

std::vector<uint32_t> balance_rows(const std::vector<uint64_t>& weights, uint32_t workers,
                                   const std::vector<double>& speeds) {
  workers = std::max(workers, 1u);
  const bool equal = equal_speeds(speeds, workers);
  std::vector<uint32_t> order(weights.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return weights[a] > weights[b]; });
  std::vector<uint64_t> load(workers, 0);
  std::vector<uint32_t> owner(weights.size(), 0);
  for (const uint32_t r : order) {
    uint32_t w = uint32_t(std::min_element(load.begin(), load.end()) - load.begin());  // first of the least
    if (!equal) {
      const auto finish = [&](uint32_t v) { return double(load[v] + weights[r]) / speeds[v]; };
      for (uint32_t v = 0; v < workers; ++v)
        if (finish(v) < finish(w)) w = v;
    }
    owner[r] = w;
    load[w] += weights[r];
  }
  return owner;
}

std::vector<uint32_t> contiguous_runs(uint32_t rows, uint32_t workers, const std::vector<double>& speeds) {
  workers = std::max(workers, 1u);
  std::vector<uint32_t> owner(rows, 0);
  if (equal_speeds(speeds, workers)) {
    for (uint32_t r = 0; r < rows; ++r) owner[r] = uint32_t(uint64_t(r) * workers / std::max(rows, 1u));
    return owner;
  }
  // worker w's run ends where the speeds before it and its own reach their share of the rows
  const double total = std::accumulate(speeds.begin(), speeds.end(), 0.0);
  double reached = 0.0;
  uint32_t r = 0;
  for (uint32_t w = 0; w < workers; ++w) {
    reached += speeds[w];
    const uint32_t end = w + 1 == workers ? rows : uint32_t(std::lround(double(rows) * reached / total));
    for (; r < std::min(end, rows); ++r) owner[r] = w;
  }
  return owner;
}

namespace {

uint64_t share_of(const std::vector<uint64_t>& weights, uint32_t workers) {
  const uint64_t total = std::accumulate(weights.begin(), weights.end(), uint64_t(0));
  return std::max<uint64_t>((total + workers - 1) / workers, 1);
}

}  // namespace

bool cuts_rows(const std::vector<uint64_t>& weights, uint32_t tiles_x, uint32_t workers) {
  const uint64_t share = share_of(weights, std::max(workers, 1u));
  return workers > 1 && tiles_x > 1 && std::any_of(weights.begin(), weights.end(), [share](uint64_t w) {
           return w * kCutShareDen > share * kCutShareNum;
         });
}

TileUnits balance_tiles(const std::vector<uint64_t>& weights, uint32_t tiles_x, uint32_t workers,
                        const std::vector<double>& speeds) {
  workers = std::max(workers, 1u);
  tiles_x = std::max(tiles_x, 1u);
  const uint64_t share = share_of(weights, workers);
  TileUnits units;
  if (!cuts_rows(weights, tiles_x, workers)) {  // whole rows, each worker's its own
    const std::vector<uint32_t> rows = balance_rows(weights, workers, speeds);
    for (const uint32_t w : rows) units.unit.insert(units.unit.end(), tiles_x, w);
    units.count = workers;
    return units;
  }
  struct Piece {
    uint32_t row, first, end;  // tiles [first, end) of the row
    uint64_t weight;
  };
  std::vector<Piece> pieces;
  for (uint32_t r = 0; r < weights.size(); ++r) {
    const uint64_t k =
        weights[r] > share ? std::min<uint64_t>((kPiecesPerShare * weights[r] + share - 1) / share, tiles_x) : 1;
    for (uint64_t p = 0; p < k; ++p) {
      const uint32_t first = uint32_t(p * tiles_x / k), end = uint32_t((p + 1) * tiles_x / k);
      pieces.push_back({r, first, end, weights[r] * (end - first) / tiles_x});
    }
  }
  std::stable_sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.weight > b.weight; });
  units.unit.assign(weights.size() * size_t(tiles_x), 0);
  for (uint32_t u = 0; u < pieces.size(); ++u) {
    const Piece& p = pieces[u];
    std::fill(units.unit.begin() + std::ptrdiff_t(size_t(p.row) * tiles_x + p.first),
              units.unit.begin() + std::ptrdiff_t(size_t(p.row) * tiles_x + p.end), u);
  }
  units.count = uint32_t(pieces.size());
  units.queued = true;
  return units;
}

}  // namespace rastercmp::cpu::fast
