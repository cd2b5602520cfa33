#include "cpu_raster/exact/binned_triangle.hpp"

#include <algorithm>
#include <bit>
#include <cstdlib>

#include "cpu_raster/exact/raster_primitive.hpp"
#include "model/errors.hpp"

namespace rastercmp::cpu {
namespace {

constexpr int32_t kTile = 64;                       // lp_limits.h TILE_SIZE
constexpr uint32_t kWholeTile = uint32_t(1) << 31;  // tile_planes: lp_setup_whole_tile

// Two's complement int32 arithmetic as the SSE and C code does it (wrapping).
int32_t add32(int32_t a, int32_t b) { return int32_t(uint32_t(a) + uint32_t(b)); }
int32_t sub32(int32_t a, int32_t b) { return int32_t(uint32_t(a) - uint32_t(b)); }
int32_t neg32(int32_t a) { return int32_t(0u - uint32_t(a)); }
int32_t mul32(int32_t a, int32_t b) { return int32_t(uint32_t(a) * uint32_t(b)); }
int32_t shl32(int32_t a, int k) { return int32_t(uint32_t(a) << k); }
// And int64 (_mm_sub_epi64, and the C additions the compiler emits as wrapping adds).
int64_t add64(int64_t a, int64_t b) { return int64_t(uint64_t(a) + uint64_t(b)); }
int64_t sub64(int64_t a, int64_t b) { return int64_t(uint64_t(a) - uint64_t(b)); }

// The planes' values at (x, y) moved from their values at (x0, y0): c - dcdx*dx + dcdy*dy (IMUL64).
void move_to(const BinnedTriangle& t, const std::array<int, 8>& index, uint32_t n, std::array<int64_t, 8>& c,
             int32_t dx, int32_t dy) {
  for (uint32_t k = 0; k < n; ++k)
    c[k] = add64(c[k], int64_t(t.plane[index[k]].dcdy) * dy - int64_t(t.plane[index[k]].dcdx) * dx);
}

}  // namespace

// The 16 values of one plane over a 4x4 grid of blocks (BUILD_MASKS, build_masks_sse) at one level
// of lp_rast_tri_tmp.h: `shift` 4 for a tile's 16x16 blocks, 2 for a 16x16 block's 4x4 blocks.
// Bit j*4 + i of `out` is set when the block's trivial-reject value is negative, of `part` when
// its trivial-accept value is.
void block_masks(const LpPlane& p, int64_t c, int shift, uint32_t& out, uint32_t& part) {
  int32_t dcdx = neg32(p.dcdx) >> kFixedOrder;
  int32_t dcdy = p.dcdy >> kFixedOrder;
  const int32_t cox = int32_t(p.eo >> kFixedOrder);
  const int32_t ei = shl32(sub32(add32(dcdy, dcdx), cox), shift);
  const int32_t cox_s = shl32(cox, shift);
  const int32_t c_hi = int32_t(c >> kFixedOrder), c_hi_minus = int32_t(sub64(c, 1) >> kFixedOrder);
  const int32_t co = add32(c_hi, cox_s);
  const int32_t cdiff = add32(sub32(ei, cox_s), sub32(c_hi_minus, c_hi));
  dcdx = shl32(dcdx, shift);
  dcdy = shl32(dcdy, shift);
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      const int32_t v = add32(add32(co, mul32(i, dcdx)), mul32(j, dcdy));
      if (v < 0) out |= 1u << (j * 4 + i);
      if (add32(v, cdiff) < 0) part |= 1u << (j * 4 + i);
    }
  }
}

// do_block_4's test of pixel (i, j) of a 4x4 block whose plane value at the corner is c:
// BUILD_MASK_LINEAR((c - 1) >> 8, -dcdx >> 8, dcdy >> 8), per sample with MULTISAMPLE.
bool stamp_pixel_passes(const LpPlane& p, int64_t c, int32_t i, int32_t j, bool multisample, uint32_t sample) {
  if (multisample) {
    const SampleOffset& s = kStandardSamples4x[sample];
    c = add64(c, (int64_t(s.y_fixed) * p.dcdy + int64_t(s.x_fixed) * neg32(p.dcdx)) >> kFixedOrder);
  }
  const int32_t c0 = int32_t(sub64(c, 1) >> kFixedOrder);
  const int32_t v = add32(add32(c0, mul32(i, neg32(p.dcdx) >> kFixedOrder)), mul32(j, p.dcdy >> kFixedOrder));
  return v >= 0;
}

int64_t wrapped_doubled_area(const std::array<FixedPoint, 3>& v) {
  const int32_t dx01 = sub32(v[0].x.raw, v[1].x.raw), dy01 = sub32(v[0].y.raw, v[1].y.raw);
  const int32_t dx20 = sub32(v[2].x.raw, v[0].x.raw), dy20 = sub32(v[2].y.raw, v[0].y.raw);
  return sub64(int64_t(dx01) * dy20, int64_t(dx20) * dy01);  // can reach 2^63: wraps as in C
}

PixelRect wrapped_triangle_bbox(const std::array<FixedPoint, 3>& v) {
  const auto [min_x, max_x] = std::minmax({v[0].x.raw, v[1].x.raw, v[2].x.raw});
  const auto [min_y, max_y] = std::minmax({v[0].y.raw, v[1].y.raw, v[2].y.raw});
  return PixelRect{min_x >> kFixedOrder, min_y >> kFixedOrder, sub32(max_x, 1) >> kFixedOrder,
                   sub32(max_y, 1) >> kFixedOrder};
}

void refuse_if_overflow_reworked(const LavapipeRules& rules) {
  if (rules.has(LavapipeRule::RasterizerOverflowReworked))
    throw NotSupportedError(
        "a primitive past llvmpipe's 32-bit set-up range (an edge of 32768 px or more, or a coordinate beyond "
        "131072 px): Mesa 26.2 changed how that arithmetic wraps, which this profile does not model "
        "(docs/lavapipe-rules.md §8.7)");
}

std::array<LpPlane, 4> lp_line_planes(const std::array<FixedPoint, 4>& corners) {
  std::array<LpPlane, 4> planes;
  for (size_t i = 0; i < 4; ++i) {
    const size_t j = (i + 1) % 4;
    const int32_t dcdx = sub32(corners[i].y.raw, corners[j].y.raw), dcdy = sub32(corners[i].x.raw, corners[j].x.raw);
    LpPlane& p = planes[i];
    p.c = sub64(int64_t(dcdx) * corners[i].x.raw, int64_t(dcdy) * corners[i].y.raw);
    if (dcdx < 0 || (dcdx == 0 && dcdy > 0)) p.c = add64(p.c, 1);  // top-left (bottom_edge_rule 0)
    p.dcdx = int32_t(uint32_t(dcdx) * uint32_t(kFixedOne));        // "dcdx *= FIXED_ONE"
    p.dcdy = int32_t(uint32_t(dcdy) * uint32_t(kFixedOne));
    int32_t eo = 0;
    if (p.dcdx < 0) eo = sub32(eo, p.dcdx);
    if (p.dcdy > 0) eo = add32(eo, p.dcdy);
    p.eo = uint32_t(eo);
  }
  return planes;
}

PixelRect wrapped_line_bbox(const std::array<FixedPoint, 4>& corners) {
  int32_t min_x = corners[0].x.raw, max_x = min_x, min_y = corners[0].y.raw, max_y = min_y;
  for (size_t i = 1; i < 4; ++i) {
    min_x = std::min(min_x, corners[i].x.raw);
    max_x = std::max(max_x, corners[i].x.raw);
    min_y = std::min(min_y, corners[i].y.raw);
    max_y = std::max(max_y, corners[i].y.raw);
  }
  constexpr int32_t kRoundUp = kFixedOne - 1;
  return PixelRect{add32(min_x, kRoundUp) >> kFixedOrder, add32(min_y, kRoundUp) >> kFixedOrder,
                   sub32(add32(max_x, kRoundUp) >> kFixedOrder, 1), sub32(add32(max_y, kRoundUp) >> kFixedOrder, 1)};
}

std::array<LpPlane, 3> lp_edge_planes(const std::array<FixedPoint, 3>& v) {
  std::array<LpPlane, 3> planes;
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3;
    const int32_t dcdx = sub32(v[i].y.raw, v[j].y.raw), dcdy = sub32(v[i].x.raw, v[j].x.raw);
    LpPlane& p = planes[i];
    p.c = sub64(int64_t(dcdx) * v[i].x.raw, int64_t(dcdy) * v[i].y.raw);
    if (dcdx < 0 || (dcdx == 0 && dcdy >= 0)) p.c = add64(p.c, 1);  // c_dec of the SSE branch
    p.dcdx = shl32(dcdx, kFixedOrder);
    p.dcdy = shl32(dcdy, kFixedOrder);
    // eo from the shifted values, selected by the signs of the unshifted ones.
    p.eo = uint32_t(sub32(dcdy >= 0 ? p.dcdy : 0, dcdx < 0 ? p.dcdx : 0));
  }
  return planes;
}

LpPlane lp_scissor_plane(const EdgePlane& scissor) {
  LpPlane p;
  p.c = scissor.c;
  p.dcdx = int32_t(scissor.dcdx * kFixedOne);
  p.dcdy = int32_t(scissor.dcdy * kFixedOne);
  p.eo = uint32_t((p.dcdx < 0 ? -p.dcdx : 0) + (p.dcdy > 0 ? p.dcdy : 0));
  return p;
}

BinnedTriangle bin_triangle(const std::array<LpPlane, 8>& planes, uint32_t plane_count, const PixelRect& bbox,
                            const PixelRect& region, const PixelRect& framebuffer, bool multisample) {
  BinnedTriangle t;
  t.plane = planes;
  t.plane_count = plane_count;
  t.multisample = multisample;
  t.tiles_x = framebuffer.x1 / kTile + 1;
  t.tiles_y = framebuffer.y1 / kTile + 1;
  t.tile_planes.assign(size_t(t.tiles_x) * size_t(t.tiles_y), 0);
  const auto bin = [&](int32_t tx, int32_t ty, uint32_t mask) {
    if (tx >= 0 && ty >= 0 && tx < t.tiles_x && ty < t.tiles_y) t.tile_planes[size_t(ty) * t.tiles_x + tx] = mask;
  };
  const uint32_t all = (1u << plane_count) - 1;
  const int32_t dx = int32_t(std::bit_floor(uint32_t((bbox.x0 ^ bbox.x1) | (bbox.y0 ^ bbox.y1))));
  if (dx < kTile) {  // one tile, every plane (the 3_4, 3_16 and 4_16 commands end in lp_rast_triangle_N)
    bin(bbox.x0 / kTile, bbox.y0 / kTile, all);
    return t;
  }
  const PixelRect trimmed = intersect(bbox, region);
  std::array<int64_t, 8> c{}, ei{}, eo{}, xstep{}, ystep{};
  for (uint32_t i = 0; i < plane_count; ++i) {
    const LpPlane& p = planes[i];
    c[i] = add64(p.c, int64_t(p.dcdy) * (trimmed.y0 / kTile) * kTile - int64_t(p.dcdx) * (trimmed.x0 / kTile) * kTile);
    ei[i] = (int64_t(sub32(p.dcdy, p.dcdx)) - int64_t(p.eo)) * kTile;
    eo[i] = int64_t(p.eo) * kTile;
    xstep[i] = -int64_t(p.dcdx) * kTile;
    ystep[i] = int64_t(p.dcdy) * kTile;
  }
  for (int32_t y = trimmed.y0 / kTile; y <= trimmed.y1 / kTile; ++y) {
    bool in = false;
    std::array<int64_t, 8> cx = c;
    for (int32_t x = trimmed.x0 / kTile; x <= trimmed.x1 / kTile; ++x) {
      bool out = false;
      uint32_t partial = 0;
      for (uint32_t i = 0; i < plane_count; ++i) {
        if (add64(cx[i], eo[i]) < 0) out = true;
        if (sub64(add64(cx[i], ei[i]), 1) < 0) partial |= 1u << i;
      }
      if (out) {
        if (in) break;  // exiting the triangle: the rest of the row is not binned
      } else {
        in = true;
        bin(x, y, partial ? partial : kWholeTile);
      }
      for (uint32_t i = 0; i < plane_count; ++i) cx[i] = add64(cx[i], xstep[i]);
    }
    for (uint32_t i = 0; i < plane_count; ++i) c[i] = add64(c[i], ystep[i]);
  }
  return t;
}

bool binned_covers(const BinnedTriangle& t, int32_t px, int32_t py, uint32_t sample) {
  if (px < 0 || py < 0) return false;
  const int32_t tx = px / kTile, ty = py / kTile;
  if (tx >= t.tiles_x || ty >= t.tiles_y) return false;
  const uint32_t mask = t.tile_planes[size_t(ty) * t.tiles_x + tx];
  if (mask == 0) return false;
  if (mask == kWholeTile) return true;
  std::array<int, 8> index{};
  uint32_t n = 0;
  for (uint32_t i = 0; i < t.plane_count; ++i)
    if (mask & (1u << i)) index[n++] = int(i);
  // lp_rast_triangle_N: the planes at the tile's corner, its 16x16 blocks.
  std::array<int64_t, 8> c{};
  for (uint32_t k = 0; k < n; ++k) c[k] = t.plane[index[k]].c;
  int32_t x = tx * kTile, y = ty * kTile;
  move_to(t, index, n, c, x, y);
  for (int shift : {4, 2}) {  // the tile's 16x16 blocks, then that block's 4x4 blocks (do_block_16)
    const int32_t size = 1 << shift;
    uint32_t out = 0, part = 0;
    for (uint32_t k = 0; k < n; ++k) block_masks(t.plane[index[k]], c[k], shift, out, part);
    if (out == 0xffff) return false;
    const int32_t bi = (px - x) / size, bj = (py - y) / size;
    const uint32_t bit = 1u << (bj * 4 + bi);
    if (!(part & bit)) return true;  // inmask = ~partmask: shaded whole (block_full_16, block_full_4)
    if (out & bit) return false;     // partial_mask = partmask & ~outmask
    move_to(t, index, n, c, bi * size, bj * size);
    x += bi * size;
    y += bj * size;
  }
  for (uint32_t k = 0; k < n; ++k)  // do_block_4
    if (!stamp_pixel_passes(t.plane[index[k]], c[k], px - x, py - y, t.multisample, sample)) return false;
  return true;
}

}  // namespace rastercmp::cpu
