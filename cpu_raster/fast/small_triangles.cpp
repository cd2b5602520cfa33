#include "cpu_raster/fast/small_triangles.hpp"

#include <array>
#include <bit>
#include <utility>

#include "cpu_raster/fast/format_dispatch.hpp"

namespace rastercmp::cpu::fast {
namespace {

// depth_test_passes (depth_sample.cpp, docs/lavapipe-rules.md §3.6), inlined for one op.
template <CompareOp Op, class T>
bool ordered(T a, T b) {
  if constexpr (Op == CompareOp::Never) return false;
  if constexpr (Op == CompareOp::Less) return a < b;
  if constexpr (Op == CompareOp::Equal) return a == b;
  if constexpr (Op == CompareOp::LessOrEqual) return a <= b;
  if constexpr (Op == CompareOp::Greater) return a > b;
  if constexpr (Op == CompareOp::NotEqual) return a != b;
  if constexpr (Op == CompareOp::GreaterOrEqual) return a >= b;
  return true;
}

template <DepthFormat F, CompareOp Op>
bool passes(uint32_t fragment, uint32_t stored) {
  if constexpr (is_float(F)) {  // unordered predicates: true whenever NaN is involved
    const float a = std::bit_cast<float>(fragment), b = std::bit_cast<float>(stored);
    if constexpr (Op == CompareOp::Never) return false;
    if constexpr (Op == CompareOp::Less) return !(a >= b);
    if constexpr (Op == CompareOp::Equal) return !(a < b) && !(a > b);
    if constexpr (Op == CompareOp::LessOrEqual) return !(a > b);
    if constexpr (Op == CompareOp::Greater) return !(a <= b);
    if constexpr (Op == CompareOp::NotEqual) return a != b;
    if constexpr (Op == CompareOp::GreaterOrEqual) return !(a < b);
    return true;
  } else {
    return ordered<Op>(fragment, stored);
  }
}

// One lane's covered pixels, in raster order.
template <DepthFormat F, CompareOp Op>
inline bool scatter_bits(const SmallBlockOutput& b, int l, uint64_t bits, uint32_t owner, bool depth_write,
                         const TileTarget& t) {
  bool wrote = false;
  const size_t origin = size_t(b.y0[l]) * size_t(t.width) + size_t(b.x0[l]);
  for (; bits != 0; bits &= bits - 1) {
    const int p = std::countr_zero(bits);
    const int dy = p >> b.grid_shift, dx = p & ((1 << b.grid_shift) - 1);
    const size_t i = origin + size_t(dy) * size_t(t.width) + size_t(dx);
    if constexpr (F != DepthFormat::None) {
      const uint32_t raw = b.grid_raw[p][l];
      if (!passes<F, Op>(raw, t.depth[i])) continue;
      if (depth_write) t.depth[i] = raw;
    }
    t.owner[i] = owner;
    wrote = true;
  }
  return wrote;
}

template <DepthFormat F, CompareOp Op>
bool scatter(const SmallBlockOutput& b, int l, uint32_t owner, int32_t row_lo, int32_t row_hi, bool depth_write,
             const TileTarget& t) {
  // Rows outside [row_lo, row_hi] belong to another worker: their bits are dropped up front.
  uint64_t bits = b.grid_bits[l];
  const int32_t first_row = row_lo - b.y0[l], last_row = row_hi - b.y0[l];
  if (first_row > 0) bits &= ~uint64_t(0) << (first_row << b.grid_shift);
  if (last_row < kGridSide - 1) bits &= (uint64_t(1) << ((last_row + 1) << b.grid_shift)) - 1u;
  return scatter_bits<F, Op>(b, l, bits, owner, depth_write, t);
}

// The 4x4 layout: every covered pixel of the block in one loop per four lanes (bit 16*k + p of
// grid_words[w] is lane 4w + k's pixel p), lanes in order and each lane's pixels in raster order,
// as scatter_bits lane by lane but without a loop exit to predict per lane.
template <DepthFormat F, CompareOp Op>
bool scatter_words(const SmallBlockOutput& b, uint32_t owner_of_lane_0, bool depth_write, const TileTarget& t) {
  alignas(32) int32_t origin[8];
  for (int l = 0; l < 8; ++l) origin[l] = b.y0[l] * t.width + b.x0[l];  // < 2^28: sides <= 16384
  bool wrote = false;
  for (int w = 0; w < 2; ++w) {
    uint64_t bits = b.grid_words[w];
    if (((b.grid_mask >> (4 * w)) & 0xFu) != 0xFu) {  // lanes that are not grid lanes drop out
      for (int k = 0; k < 4; ++k)
        if (!((b.grid_mask >> (4 * w + k)) & 1u)) bits &= ~(uint64_t(0xFFFF) << (16 * k));
    }
    for (; bits != 0; bits &= bits - 1) {
      const int q = std::countr_zero(bits);
      const int l = 4 * w + (q >> 4), p = q & 15;
      const size_t i = size_t(origin[l] + (p >> kSmallGridShift) * t.width + (p & (kSmallGridSide - 1)));
      if constexpr (F != DepthFormat::None) {
        const uint32_t raw = b.grid_raw[p][l];
        if (!passes<F, Op>(raw, t.depth[i])) continue;
        if (depth_write) t.depth[i] = raw;
      }
      t.owner[i] = owner_of_lane_0 + uint32_t(l);
      wrote = true;
    }
  }
  return wrote;
}

template <DepthFormat F, CompareOp Op>
bool scatter_block(const SmallBlockOutput& b, uint32_t owner_of_lane_0, bool depth_write, const TileTarget& t) {
  if (b.grid_shift == kSmallGridShift) return scatter_words<F, Op>(b, owner_of_lane_0, depth_write, t);
  bool wrote = false;
  for (uint32_t lanes = b.grid_mask; lanes != 0; lanes &= lanes - 1) {
    const int l = std::countr_zero(lanes);
    wrote |= scatter_bits<F, Op>(b, l, b.grid_bits[l], owner_of_lane_0 + uint32_t(l), depth_write, t);
  }
  return wrote;
}

struct Blocks {
  template <DepthFormat F, CompareOp Op>
  static constexpr GridBlockFn get() {
    return &scatter_block<F, Op>;
  }
};
constexpr auto kBlocks = kernel_table<Blocks>();  // [format][op] (format_dispatch.hpp)

struct Scatters {
  template <DepthFormat F, CompareOp Op>
  static constexpr GridScatterFn get() {
    return &scatter<F, Op>;
  }
};
constexpr auto kScatters = kernel_table<Scatters>();

}  // namespace

KernelJob SmallBlockOutput::job(int lane, uint32_t owner, CompareOp op, int32_t row_lo, int32_t row_hi) const {
  KernelJob j;
  j.rect = PixelRect{x0[lane], row_lo, x1[lane], row_hi};
  j.origin_x = origin_x[lane];
  for (int i = 0; i < 3; ++i) {
    j.g_minus_1[i] = edge_minus_1(lane, i, j.origin_x, row_lo);
    j.gx[i] = gx[i][lane];
    j.gy[i] = gy[i][lane];
  }
  j.a0 = a0[lane];
  j.dzdx = dzdx[lane];
  j.dzdy = dzdy[lane];
  j.offset = 0.0f;
  j.owner = owner;
  j.op = op;
  return j;
}

GridBlockFn select_grid_block(DepthFormat format, CompareOp op) { return select_kernel(kBlocks, format, op); }

GridScatterFn select_grid_scatter(DepthFormat format, CompareOp op) { return select_kernel(kScatters, format, op); }

}  // namespace rastercmp::cpu::fast
