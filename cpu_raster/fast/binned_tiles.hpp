// Coverage of a binned primitive (llvmpipe's wrapping set-up, cpu_raster/exact/binned_triangle.hpp)
// over one whole 64x64 tile at once: binned_covers' walk of lp_rast_triangle_N (the tile's 16x16
// blocks, a block's 4x4 blocks, do_block_4's pixels) done once per block instead of once per pixel.
#pragma once

#include <array>
#include <cstdint>

#include "cpu_raster/exact/binned_triangle.hpp"

namespace rastercmp::cpu::fast {

inline constexpr int32_t kBinTile = 64;  // lp_limits.h TILE_SIZE, as bin_triangle's

// rows[j] bit i: binned_covers(t, tx * 64 + i, ty * 64 + j, sample), for a tile inside t's tiles.
void binned_tile_coverage(const BinnedTriangle& t, int32_t tx, int32_t ty, uint32_t sample,
                          std::array<uint64_t, kBinTile>& rows);

}  // namespace rastercmp::cpu::fast
