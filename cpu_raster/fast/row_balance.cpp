#include "cpu_raster/fast/row_balance.hpp"

#include <algorithm>
#include <numeric>

namespace rastercmp::cpu::fast {

uint64_t tile_row_weight(uint64_t blocks, uint32_t tiles_x) {
  return blocks * kRowWeightPerBlock +
         uint64_t(tiles_x) * (kRowWeightPerClearedTile + (blocks > 0 ? kRowWeightPerFilledTile : 0));
}

std::vector<uint32_t> balance_rows(const std::vector<uint64_t>& weights, uint32_t workers) {
  workers = std::max(workers, 1u);
  std::vector<uint32_t> order(weights.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return weights[a] > weights[b]; });
  std::vector<uint64_t> load(workers, 0);
  std::vector<uint32_t> owner(weights.size(), 0);
  for (const uint32_t r : order) {
    const uint32_t w = uint32_t(std::min_element(load.begin(), load.end()) - load.begin());  // first of the least
    owner[r] = w;
    load[w] += weights[r];
  }
  return owner;
}

}  // namespace rastercmp::cpu::fast
