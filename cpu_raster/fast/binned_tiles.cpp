#include "cpu_raster/fast/binned_tiles.hpp"

#include "cpu_raster/exact/raster_primitive.hpp"

namespace rastercmp::cpu::fast {
namespace {

constexpr uint32_t kWholeTile = uint32_t(1) << 31;  // BinnedTriangle::tile_planes: lp_setup_whole_tile

// binned_triangle.cpp's wrapping int64 addition.
int64_t add64(int64_t a, int64_t b) { return int64_t(uint64_t(a) + uint64_t(b)); }

// The planes binned for the tile, and their values at a block's corner.
struct TilePlanes {
  std::array<const LpPlane*, 8> plane{};
  std::array<int64_t, 8> c{};
  uint32_t count = 0;

  void move(int32_t dx, int32_t dy) {  // binned_triangle.cpp move_to (IMUL64)
    for (uint32_t k = 0; k < count; ++k)
      c[k] = add64(c[k], int64_t(plane[k]->dcdy) * dy - int64_t(plane[k]->dcdx) * dx);
  }
};

// block_masks (exact/binned_triangle.hpp, BUILD_MASKS) over every binned plane: bit j*4 + i of out / part.
void block_masks(const TilePlanes& planes, int shift, uint32_t& out, uint32_t& part) {
  out = part = 0;
  for (uint32_t k = 0; k < planes.count; ++k) cpu::block_masks(*planes.plane[k], planes.c[k], shift, out, part);
}

// stamp_pixel_passes (exact/binned_triangle.hpp, do_block_4) for every binned plane.
bool stamp_pixel_passes(const TilePlanes& planes, int32_t i, int32_t j, bool multisample, uint32_t sample) {
  for (uint32_t k = 0; k < planes.count; ++k)
    if (!cpu::stamp_pixel_passes(*planes.plane[k], planes.c[k], i, j, multisample, sample)) return false;
  return true;
}

void set_block(std::array<uint64_t, kBinTile>& rows, int32_t x, int32_t y, int32_t size) {
  const uint64_t bits = (size == 64 ? ~uint64_t(0) : ((uint64_t(1) << size) - 1)) << x;
  for (int32_t j = y; j < y + size; ++j) rows[size_t(j)] |= bits;
}

// One 4x4 block of a partial 16x16 block (planes at its corner (x, y) in the tile).
void partial_block_4(const BinnedTriangle& t, const TilePlanes& planes, int32_t x, int32_t y, uint32_t sample,
                     std::array<uint64_t, kBinTile>& rows) {
  for (int32_t j = 0; j < 4; ++j)
    for (int32_t i = 0; i < 4; ++i)
      if (stamp_pixel_passes(planes, i, j, t.multisample, sample)) rows[size_t(y + j)] |= uint64_t(1) << (x + i);
}

// One partial 16x16 block (planes at its corner (x, y) in the tile): its 4x4 blocks as binned_covers
// judges them: none when all 16 are out; else whole when not partial (tested before out), none
// when out, pixel by pixel otherwise.
void partial_block_16(const BinnedTriangle& t, TilePlanes planes, int32_t x, int32_t y, uint32_t sample,
                      std::array<uint64_t, kBinTile>& rows) {
  uint32_t out, part;
  block_masks(planes, 2, out, part);
  if (out == 0xffff) return;
  for (int32_t bj = 0; bj < 4; ++bj) {
    for (int32_t bi = 0; bi < 4; ++bi) {
      const uint32_t bit = 1u << (bj * 4 + bi);
      if (!(part & bit)) {
        set_block(rows, x + 4 * bi, y + 4 * bj, 4);
      } else if (!(out & bit)) {
        TilePlanes block = planes;
        block.move(4 * bi, 4 * bj);
        partial_block_4(t, block, x + 4 * bi, y + 4 * bj, sample, rows);
      }
    }
  }
}

}  // namespace

void binned_tile_coverage(const BinnedTriangle& t, int32_t tx, int32_t ty, uint32_t sample,
                          std::array<uint64_t, kBinTile>& rows) {
  rows.fill(0);
  const uint32_t mask = t.tile_planes[size_t(ty) * size_t(t.tiles_x) + size_t(tx)];
  if (mask == 0) return;
  if (mask == kWholeTile) return set_block(rows, 0, 0, kBinTile);
  TilePlanes planes;
  for (uint32_t i = 0; i < t.plane_count; ++i) {
    if (!(mask & (1u << i))) continue;
    planes.plane[planes.count] = &t.plane[i];
    planes.c[planes.count++] = t.plane[i].c;
  }
  planes.move(tx * kBinTile, ty * kBinTile);  // lp_rast_triangle_N: the planes at the tile's corner
  uint32_t out, part;
  block_masks(planes, 4, out, part);
  if (out == 0xffff) return;
  for (int32_t bj = 0; bj < 4; ++bj) {
    for (int32_t bi = 0; bi < 4; ++bi) {
      const uint32_t bit = 1u << (bj * 4 + bi);
      if (!(part & bit)) {  // inmask = ~partmask: shaded whole (block_full_16)
        set_block(rows, 16 * bi, 16 * bj, 16);
      } else if (!(out & bit)) {  // partial_mask = partmask & ~outmask
        TilePlanes block = planes;
        block.move(16 * bi, 16 * bj);
        partial_block_16(t, block, 16 * bi, 16 * bj, sample, rows);
      }
    }
  }
}

}  // namespace rastercmp::cpu::fast
