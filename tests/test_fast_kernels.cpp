// Unit tests of the fast path's rasterizing stages against the exact path's own functions and
// against each other: the eight- and sixteen-wide small-triangle set-ups (packed grid words, the
// window compositors, the pair set-up), the 32-bit "G" edge form, the row columns, the vector tile
// kernels against the scalar one and the binned tiles. test_fast_exact_rows.cpp holds the vector
// exact rows, test_fast_lean_setup.cpp the lean set-ups; test_fast_units.cpp the stages around
// them (vertices, clears, the pool, block rows, row balance, depth bounds, exact rows).
#include <gtest/gtest.h>
#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <random>
#include <vector>

#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/edge_plane.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/fixed_point.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "cpu_raster/fast/binned_tiles.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/fast_vertices.hpp"
#include "cpu_raster/fast/small_triangles.hpp"
#include "cpu_raster/fast/small_window.hpp"
#include "cpu_raster/fast/tile_edges.hpp"
#include "cpu_raster/fast/tile_raster.hpp"
#include "tests/test_fast_support.hpp"

namespace rastercmp::cpu::fast {
namespace {

// Eight triangles for the eight-wide set-up: lane l's corner k is the l-th vertex added for k.
struct EightTriangles {
  std::vector<FastVertex> vertices;
  std::vector<uint32_t> corners[3];
  void add(int k, float x, float y, float z) {
    corners[k].push_back(uint32_t(vertices.size()));
    vertices.push_back(FastVertex{x, y, z, 0});
  }
  // The block over the eight lanes (depth state left at its defaults); valid while this lives.
  SmallBlockInput input(const PixelRect& region) const {
    SmallBlockInput in;
    in.vertices = vertices.data();
    for (int k = 0; k < 3; ++k) in.corners[k] = corners[k].data();
    in.count = 8;
    in.region = region;
    return in;
  }
};

// Eight triangles of about a pixel: the block takes the packed 4x4 layout, and grid_words holds
// each grid lane's 16 bits (lane 4w + k at bit 16k of word w) equal to its grid_bits.
TEST(FastSmallTriangles, PackedGridWordsHoldEachLanesBits) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the eight-wide set-up does not run";
  fast_test::Random r(11);
  for (int trial = 0; trial < 200; ++trial) {
    EightTriangles block;
    for (int l = 0; l < 8; ++l) {
      const float cx = float(r.range(4.0, 60.0)), cy = float(r.range(4.0, 60.0));
      for (int k = 0; k < 3; ++k) {
        const float x = cx + float(r.range(-1.2, 1.2)), y = cy + float(r.range(-1.2, 1.2));
        block.add(k, x, y, float(r.range(0.0, 1.0)));
      }
    }
    SmallBlockInput in = block.input(PixelRect{0, 0, 63, 63});
    in.depth.format = DepthFormat::D32Sfloat;
    SmallBlockOutput out;
    setup_small_block_avx2(in, out);
    if (out.grid_mask == 0) continue;
    bool fits = true;
    for (int l = 0; l < 8; ++l)
      if ((out.grid_mask >> l) & 1u)
        fits = fits && out.x1[l] - out.x0[l] < kSmallGridSide && out.y1[l] - out.y0[l] < kSmallGridSide;
    ASSERT_EQ(out.grid_shift, fits ? kSmallGridShift : 3) << "trial " << trial;
    if (!fits) continue;
    for (int l = 0; l < 8; ++l) {
      if (!((out.grid_mask >> l) & 1u)) continue;
      EXPECT_EQ((out.grid_words[l / 4] >> (16 * (l % 4))) & 0xFFFFu, out.grid_bits[l])
          << "trial " << trial << " lane " << l;
    }
  }
}

// Eight overlapping triangles of a few pixels, in the 8x8 layout: the eight-wide set-up hands the
// block to the window compositor, whose result equals the grid lanes' scatter (the same set-up
// without window_ok) for every depth format and compare op, with and without depth writes, clamp
// and FMA, also when only some of the block's rows are drawn (another worker's rows).
void expect_window_equals_grid_scatter(SmallSetupFn setup, WindowBlockFn (*select_window)(DepthFormat, CompareOp)) {
  fast_test::Random r(23);
  constexpr int32_t kSide = 48;
  int windows = 0;
  for (int trial = 0; trial < 600; ++trial) {
    EightTriangles block;
    const float bx = float(r.range(8.0, 20.0)), by = float(r.range(8.0, 30.0));
    for (int l = 0; l < 8; ++l) {  // a row of cells of about 3 px, jittered enough to overlap
      const float cx = bx + 3.0f * float(l / 2) + float(r.range(-1.0, 1.0)), cy = by + float(r.range(-1.0, 1.0));
      for (int k = 0; k < 3; ++k) {
        const float x = cx + float(r.range(-3.0, 3.0)), y = cy + float(r.range(-3.0, 3.0));
        block.add(k, x, y, float(r.range(-0.2, 1.2)));
      }
    }
    SmallBlockInput in = block.input(PixelRect{0, 0, kSide - 1, kSide - 1});
    in.depth.format = DepthFormat(trial % 4);
    in.depth.op = in.depth.format == DepthFormat::None ? CompareOp::Always : CompareOp(r.below(8));
    in.depth.write = in.depth.format != DepthFormat::None && !r.chance(0.2);
    in.depth.clamp = r.chance(0.3);
    in.depth.zmin = 0.2f, in.depth.zmax = 0.7f;
    in.depth.fma = r.chance(0.5);
    SmallBlockOutput grid, window;
    setup(in, grid);  // window_ok false: the grid evaluation
    in.window_ok = true;
    setup(in, window);
    ASSERT_FALSE(grid.window);
    if (!window.window) continue;
    ++windows;
    std::vector<uint32_t> stored(kSide * kSide);
    for (uint32_t& v : stored) {
      const float z = float(r.range(0.0, 1.0));
      v = in.depth.format == DepthFormat::D32Sfloat  ? std::bit_cast<uint32_t>(z)
          : in.depth.format == DepthFormat::D16Unorm ? uint32_t(z * 65535.0f)
                                                     : uint32_t(z * 16777215.0f);
    }
    std::vector<uint32_t> owner_a(kSide * kSide, kOwnerBackground), owner_b = owner_a, depth_a = stored,
                                                                    depth_b = stored;
    const TileTarget a{owner_a.data(), in.depth.format == DepthFormat::None ? nullptr : depth_a.data(), kSide, kSide};
    const TileTarget b{owner_b.data(), in.depth.format == DepthFormat::None ? nullptr : depth_b.data(), kSide, kSide};
    // every row, or a cut at a row inside the block (the rows of the other worker are not drawn)
    int32_t row_lo = window.grid_y0, row_hi = window.grid_y1;
    if (trial % 3 == 1) row_lo = std::min(row_hi, row_lo + 2);
    if (trial % 3 == 2) row_hi = std::max(row_lo, row_hi - 2);
    for (uint32_t lanes = grid.grid_mask; lanes != 0; lanes &= lanes - 1) {
      const int l = std::countr_zero(lanes);  // the scatter takes rows within the lane's own (draw_small)
      const int32_t lo = std::max(row_lo, grid.y0[l]), hi = std::min(row_hi, grid.y1[l]);
      if (lo <= hi)
        select_grid_scatter(in.depth.format, in.depth.op)(grid, l, 100 + uint32_t(l), lo, hi, in.depth.write, a);
    }
    select_window(in.depth.format, in.depth.op)(window, 100, row_lo, row_hi, in.depth, b);
    ASSERT_EQ(owner_a, owner_b) << "trial " << trial;
    ASSERT_EQ(depth_a, depth_b) << "trial " << trial;
  }
  EXPECT_GT(windows, 300);  // most blocks of this shape take the window
}

TEST(FastSmallTriangles, WindowCompositorEqualsGridScatter) {
  if (!host_has_avx512()) GTEST_SKIP() << "host without AVX-512: the sixteen-pixel window compositor does not run";
  expect_window_equals_grid_scatter(&setup_small_block_avx512, &select_window_block_avx512);
}

TEST(FastSmallTriangles, EightPixelWindowCompositorEqualsGridScatter) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the eight-pixel window compositor does not run";
  expect_window_equals_grid_scatter(&setup_small_block_avx2, &select_window_block_avx2);
}

// Attachment memory for the compositor's tile test: rows of 8 KiB whose columns 0-63 end a page
// and whose columns 64-1087 fill the next one, which is read-only while `guarded`.
struct GuardedRows {
  static constexpr int32_t kWidth = 2048, kHeight = 48;
  static constexpr size_t kPage = 4096, kRowBytes = kWidth * sizeof(uint32_t);
  static constexpr size_t kBytes = kHeight * kRowBytes + kRowBytes;
  char* base = nullptr;
  GuardedRows() {
    void* p = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    base = p == MAP_FAILED ? nullptr : static_cast<char*>(p);
  }
  ~GuardedRows() {
    if (base != nullptr) munmap(base, kBytes);
  }
  uint32_t* pixels() const { return reinterpret_cast<uint32_t*>(base + kPage - 64 * sizeof(uint32_t)); }
  bool guard(bool guarded) const {
    for (int32_t y = 0; y < kHeight; ++y)
      if (mprotect(base + size_t(y) * kRowBytes + kPage, kPage, guarded ? PROT_READ : PROT_READ | PROT_WRITE) != 0)
        return false;
    return true;
  }
};

// The eight-pixel compositor stores a window row's last unit whole only where the unit's columns
// past the window lie in the tile of the window's last column (this worker's): blocks whose
// windows end a few columns before column 64, the next tile's first, drawn with columns 64 and
// on read-only (a store into them stops the test with SIGSEGV), and the bytes of columns 0-63
// equal to the grid lanes' scatter.
TEST(FastSmallTriangles, EightPixelWindowCompositorWritesNoColumnOfTheNextTile) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the eight-pixel window compositor does not run";
  fast_test::Random r(31);
  GuardedRows owner_a, owner_b, depth_a, depth_b;
  ASSERT_TRUE(owner_a.base && owner_b.base && depth_a.base && depth_b.base);
  int crossing = 0;
  for (int trial = 0; trial < 400; ++trial) {
    EightTriangles block;
    const float bx = float(r.range(36.0, 54.0)), by = float(r.range(8.0, 30.0));
    for (int l = 0; l < 8; ++l) {
      const float cx = bx + 3.0f * float(l / 2) + float(r.range(-1.0, 1.0)), cy = by + float(r.range(-1.0, 1.0));
      for (int k = 0; k < 3; ++k)
        block.add(k, cx + float(r.range(-3.0, 3.0)), cy + float(r.range(-3.0, 3.0)), float(r.range(0.0, 1.0)));
    }
    SmallBlockInput in = block.input(PixelRect{0, 0, 63, GuardedRows::kHeight - 1});
    in.depth.format = DepthFormat::D32Sfloat;
    in.depth.op = CompareOp(r.below(8));
    in.depth.write = !r.chance(0.2);
    SmallBlockOutput grid, window;
    setup_small_block_avx2(in, grid);
    in.window_ok = true;
    setup_small_block_avx2(in, window);
    if (!window.window) continue;
    const int32_t width = window.grid_x1 - window.grid_x0 + 1;
    crossing += window.grid_x0 + 8 * ((width + 7) / 8) > 64 ? 1 : 0;
    for (int32_t y = 0; y < GuardedRows::kHeight; ++y)
      for (int32_t x = 0; x < 64; ++x) {
        const size_t i = size_t(y) * GuardedRows::kWidth + size_t(x);
        owner_a.pixels()[i] = owner_b.pixels()[i] = kOwnerBackground;
        depth_a.pixels()[i] = depth_b.pixels()[i] = std::bit_cast<uint32_t>(float(r.range(0.0, 1.0)));
      }
    const TileTarget a{owner_a.pixels(), depth_a.pixels(), GuardedRows::kWidth, GuardedRows::kHeight};
    const TileTarget b{owner_b.pixels(), depth_b.pixels(), GuardedRows::kWidth, GuardedRows::kHeight};
    for (uint32_t lanes = grid.grid_mask; lanes != 0; lanes &= lanes - 1) {
      const int l = std::countr_zero(lanes);
      select_grid_scatter(in.depth.format, in.depth.op)(grid, l, 100 + uint32_t(l), grid.y0[l], grid.y1[l],
                                                        in.depth.write, a);
    }
    ASSERT_TRUE(owner_b.guard(true) && depth_b.guard(true));
    select_window_block_avx2(in.depth.format, in.depth.op)(window, 100, window.grid_y0, window.grid_y1, in.depth, b);
    ASSERT_TRUE(owner_b.guard(false) && depth_b.guard(false));
    for (int32_t y = 0; y < GuardedRows::kHeight; ++y)
      for (int32_t x = 0; x < 64; ++x) {
        const size_t i = size_t(y) * GuardedRows::kWidth + size_t(x);
        ASSERT_EQ(owner_a.pixels()[i], owner_b.pixels()[i]) << "trial " << trial << " x " << x << " y " << y;
        ASSERT_EQ(depth_a.pixels()[i], depth_b.pixels()[i]) << "trial " << trial << " x " << x << " y " << y;
      }
  }
  EXPECT_GT(crossing, 50);  // windows whose last unit reaches into the next tile
}

// What a set-up output says about lane l that the drawing reads: its rectangle, and by class the
// covered pixels with their raw depth (grid lanes, decoded with the output's own layout), the
// kernel job, or the compositor's edge values and plane (window blocks).
std::vector<int64_t> lane_meaning(const SmallBlockOutput& o, int l, DepthFormat format) {
  const auto bits = [](float f) { return int64_t(std::bit_cast<uint32_t>(f)); };
  std::vector<int64_t> m{o.x0[l], o.y0[l], o.x1[l], o.y1[l]};
  if (o.window) {
    for (int k = 0; k < 3; ++k) m.insert(m.end(), {o.e_window[k][l], o.gx[k][l], o.gy[k][l]});
    m.insert(m.end(), {bits(o.a0[l]), bits(o.dzdx[l]), bits(o.dzdy[l])});
  } else if ((o.grid_mask >> l) & 1u) {
    const int side = 1 << o.grid_shift;
    for (uint64_t b = o.grid_bits[l]; b != 0; b &= b - 1) {
      const int p = std::countr_zero(b);
      m.insert(m.end(), {p % side, p / side, format == DepthFormat::None ? 0 : int64_t(o.grid_raw[p][l])});
    }
    // the packed words, where the layout has them, hold the same bits
    m.push_back(o.grid_shift != kSmallGridShift ||
                ((o.grid_words[l / 4] >> (16 * (l % 4))) & 0xFFFFu) == o.grid_bits[l]);
  } else {
    const KernelJob j = o.job(l, 1, CompareOp::Less, o.y0[l], o.y1[l]);
    m.insert(m.end(), {j.origin_x, bits(j.a0), bits(j.dzdx), bits(j.dzdy)});
    for (int k = 0; k < 3; ++k) m.insert(m.end(), {j.g_minus_1[k], j.gx[k], j.gy[k]});
  }
  return m;
}

// The sixteen-wide set-up describes each of its two blocks as the eight-wide set-up does: the
// same lane classes, rectangles, covered pixels and raw depths, kernel jobs and window blocks,
// over triangles of every size class, flagged corners, cut regions, partial second blocks, every
// depth format, cull mode and winding.
TEST(FastSmallTriangles, PairSetupEqualsTwoBlocks) {
  if (!host_has_avx512()) GTEST_SKIP() << "host without AVX-512: the sixteen-wide set-up does not run";
  fast_test::Random r(31);
  int seen[4] = {0, 0, 0, 0};  // scalar, job, grid, window lanes
  for (int trial = 0; trial < 6000; ++trial) {
    EightTriangles blocks[2];
    const float spread = float(trial % 4 == 0 ? 1.2 : trial % 4 == 1 ? 3.0 : trial % 4 == 2 ? 6.0 : 20.0);
    for (EightTriangles& block : blocks) {
      const float bx = float(r.range(-8.0, 120.0)), by = float(r.range(-8.0, 120.0));
      for (int l = 0; l < 8; ++l) {
        const float cx = bx + float(r.range(-4.0, 4.0)), cy = by + float(r.range(-4.0, 4.0));
        const float lane_spread = r.chance(0.1) ? 12.0f : spread;
        for (int k = 0; k < 3; ++k)
          block.add(k, cx + float(r.range(-lane_spread, lane_spread)), cy + float(r.range(-lane_spread, lane_spread)),
                    float(r.range(-0.2, 1.2)));
        if (r.chance(0.05)) block.vertices.back().flags = r.chance(0.5) ? kVertexSnapFailed : 1u;
      }
    }
    const int32_t rx = int32_t(r.below(24)), ry = int32_t(r.below(24));
    SmallBlockInput in0 =
        blocks[0].input(PixelRect{rx, ry, rx + 40 + int32_t(r.below(80)), ry + 40 + int32_t(r.below(80))});
    in0.depth.format = DepthFormat(r.below(4));
    in0.depth.op = in0.depth.format == DepthFormat::None ? CompareOp::Always : CompareOp(r.below(8));
    in0.depth.write = r.chance(0.8);
    in0.depth.clamp = r.chance(0.3);
    in0.depth.zmin = 0.2f, in0.depth.zmax = 0.7f;
    in0.depth.fma = r.chance(0.5);
    in0.cull = CullMode(r.below(4));
    in0.front_ccw = r.chance(0.5);
    in0.window_ok = r.chance(0.7);
    SmallBlockInput in1 = in0;
    for (int k = 0; k < 3; ++k) in1.corners[k] = blocks[1].corners[k].data();
    in1.count = r.chance(0.7) ? 8 : 1 + r.below(8);
    for (uint32_t l = in1.count; l < 8; ++l)  // lanes past count repeat the block's first (fill_block_corners)
      for (auto& corners : blocks[1].corners) corners[l] = corners[0];
    SmallBlockOutput single[2], pair[2];
    setup_small_block_avx512(in0, single[0]);
    setup_small_block_avx512(in1, single[1]);
    setup_small_pair_avx512(in0, in1, pair[0], pair[1]);
    for (int b = 0; b < 2; ++b) {
      const SmallBlockOutput &s = single[b], &p = pair[b];
      ASSERT_EQ(s.scalar_mask, p.scalar_mask) << "trial " << trial << " block " << b;
      ASSERT_EQ(s.job_mask, p.job_mask) << "trial " << trial << " block " << b;
      ASSERT_EQ(s.grid_mask, p.grid_mask) << "trial " << trial << " block " << b;
      seen[0] += std::popcount(s.scalar_mask), seen[1] += std::popcount(s.job_mask);
      if (s.grid_mask == 0) continue;
      ASSERT_EQ(s.window, p.window) << "trial " << trial << " block " << b;
      seen[s.window ? 3 : 2] += std::popcount(s.grid_mask);
      EXPECT_EQ(std::vector<int32_t>({s.grid_x0, s.grid_y0, s.grid_x1, s.grid_y1}),
                std::vector<int32_t>({p.grid_x0, p.grid_y0, p.grid_x1, p.grid_y1}))
          << "trial " << trial << " block " << b;
      for (int l = 0; l < 8; ++l) {
        if (((s.grid_mask | s.job_mask) >> l) & 1u) {
          ASSERT_EQ(lane_meaning(s, l, in0.depth.format), lane_meaning(p, l, in0.depth.format))
              << "trial " << trial << " block " << b << " lane " << l;
        }
      }
    }
  }
  for (int c = 0; c < 4; ++c) EXPECT_GT(seen[c], 500) << "lane class " << c;
}

// The trailing-run check's eight-wide planes (trailing_depth_planes_avx2) raise the MXCSR flags
// DenormalWatch reads exactly when the scalar loop's two triangle_depth_plane calls do: per
// triangle (the lane repeated, as a last short group is) and per group of eight, with denormals
// kept and under FTZ|DAZ. The triangles' z and coordinates are drawn to reach denormals: tiny
// and denormal z, near-equal z, tiny coordinates, slivers.
TEST(FastSmallTriangles, TrailingPlanesRaiseTheScalarLoopsFlags) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "the host runs no AVX2";
  std::mt19937 rng(37);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto coordinate = [&]() -> float {
    switch (rng() % 4) {
      case 0: return std::ldexp(unit(rng), -int(rng() % 140));  // down to denormals
      case 1: return 0.5f;
      default: return 2048.0f * unit(rng);
    }
  };
  const auto depth = [&](float near) -> float {
    switch (rng() % 5) {
      case 0: return std::ldexp(unit(rng), -int(rng() % 150));
      case 1: return 0.0f;
      case 2: return std::nextafter(near, 1.0f);  // one ulp from another corner
      default: return unit(rng);
    }
  };
  volatile float sink = 0.0f;
  const auto scalar_met = [&](const FastVertex* v, const uint32_t (&c)[3][8], int lanes) {
    const DenormalWatch watch;
    for (int l = 0; l < lanes; ++l) {
      const auto w = [&](uint32_t i) { return WindowVertex{v[i].x, v[i].y, v[i].z}; };
      for (const std::array<WindowVertex, 3>& t : {std::array<WindowVertex, 3>{w(c[0][l]), w(c[1][l]), w(c[2][l])},
                                                   std::array<WindowVertex, 3>{w(c[0][l]), w(c[2][l]), w(c[1][l])}}) {
        const DepthPlane p = triangle_depth_plane(t, 0.5f);
        sink = p.a0;
        sink = p.dzdx;
        sink = p.dzdy;
      }
    }
    return watch.met();
  };
  const auto vector_met = [&](const FastVertex* v, const uint32_t (&c)[3][8]) {
    const DenormalWatch watch;
    sink = float(trailing_depth_planes_avx2(v, c));
    return watch.met();
  };
  int outcomes[2] = {0, 0};
  for (const bool flushed : {false, true}) {
    const ScopedDenormalMode mode(flushed);
    for (int trial = 0; trial < 4000; ++trial) {
      std::vector<FastVertex> v;
      for (int i = 0; i < 24; ++i) {
        const float near = v.empty() ? unit(rng) : v.back().z;
        v.push_back(FastVertex{coordinate(), coordinate(), depth(near), 0});
      }
      if (rng() % 4 == 0) v[2].y = std::nextafter(v[1].y, 4096.0f);  // a sliver
      uint32_t group[3][8];
      for (uint32_t l = 0; l < 8; ++l)
        for (uint32_t k = 0; k < 3; ++k) group[k][l] = 3 * l + k;
      ASSERT_EQ(scalar_met(v.data(), group, 8), vector_met(v.data(), group)) << "trial " << trial;
      uint32_t one[3][8];
      const uint32_t l = rng() % 8;
      for (uint32_t k = 0; k < 3; ++k) std::fill(one[k], one[k] + 8, group[k][l]);
      const bool met = scalar_met(v.data(), one, 1);
      ASSERT_EQ(met, vector_met(v.data(), one)) << "trial " << trial << " lane " << l << " flushed " << flushed;
      ++outcomes[met ? 1 : 0];
    }
  }
  EXPECT_GT(outcomes[0], 1000);
  EXPECT_GT(outcomes[1], 1000);
}

// G > 0 exactly where the exact 64-bit edge value E > 0, over random rectangles of a tile.
TEST(FastTileEdges, GFormAgreesWithExactEdgeValues) {
  fast_test::Random r(11);
  for (int trial = 0; trial < 400; ++trial) {
    FastTriangle t;
    const int32_t spread = trial % 2 ? 40 * kFixedOne : 3000 * kFixedOne;
    const int32_t cx = int32_t(r.below(2048)) * kFixedOne, cy = int32_t(r.below(2048)) * kFixedOne;
    for (int k = 0; k < 3; ++k) {
      t.x_fixed[k] = cx + int32_t(r.below(uint32_t(2 * spread))) - spread;
      t.y_fixed[k] = cy + int32_t(r.below(uint32_t(2 * spread))) - spread;
    }
    const int32_t tx = int32_t(r.below(32)) * kTileSize, ty = int32_t(r.below(32)) * kTileSize;
    const int32_t x0 = tx + int32_t(r.below(64)), y0 = ty + int32_t(r.below(64));
    const PixelRect rect{x0, y0, x0 + int32_t(r.below(uint32_t(tx + 64 - x0))),
                         y0 + int32_t(r.below(uint32_t(ty + 64 - y0)))};
    KernelJob job;
    const EdgeSetup setup = setup_tile_edges(t, rect, job);
    ASSERT_NE(setup.fit, EdgeFit::Scalar);
    for (int32_t py = rect.y0; py <= rect.y1; ++py) {
      for (int32_t px = rect.x0; px <= rect.x1; ++px) {
        bool exact_in = true, g_in = true;
        for (int i = 0; i < 3; ++i) {
          const int j = (i + 1) % 3;
          const EdgePlane e =
              make_edge(FixedPoint{Fixed24_8{t.x_fixed[i]}, Fixed24_8{t.y_fixed[i]}},
                        FixedPoint{Fixed24_8{t.x_fixed[j]}, Fixed24_8{t.y_fixed[j]}}, TieBreak::TopLeft);
          exact_in = exact_in && edge_value(e, int64_t(px) * kFixedOne, int64_t(py) * kFixedOne) > 0;
          const int64_t g_minus_1 = int64_t(job.g_minus_1[i]) + int64_t(job.gx[i]) * (px - job.origin_x) +
                                    int64_t(job.gy[i]) * (py - rect.y0);
          g_in = g_in && g_minus_1 >= 0;
        }
        if (setup.fit == EdgeFit::None) {
          ASSERT_FALSE(exact_in) << "rejected rectangle covers (" << px << "," << py << ")";
        } else {
          ASSERT_EQ(exact_in, g_in) << "trial " << trial << " pixel (" << px << "," << py << ")";
        }
        if (setup.all_in) {
          ASSERT_TRUE(exact_in);
        }
      }
    }
  }
}

// The AVX2 kernel's covered columns of each row (row_columns_avx2.hpp) are exactly the pixels whose
// G - 1 >= 0 for every edge, over random triangles from one pixel to thousands wide, near-horizontal
// and near-vertical edges (quotients far outside the tile), horizontal and vertical ones (flat
// edges), and rectangles anywhere in a tile.
TEST(FastTileEdges, RowColumnsAreTheCoveredPixelsOfEachRow) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the row-column kernel does not run";
  fast_test::Random r(23);
  int64_t covered_rows = 0, empty_rows = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    FastTriangle t;
    const int32_t spreads[] = {2 * kFixedOne, 40 * kFixedOne, 3000 * kFixedOne, 16000 * kFixedOne};
    const int32_t spread = spreads[trial % 4];
    const int32_t cx = int32_t(r.below(2048)) * kFixedOne, cy = int32_t(r.below(2048)) * kFixedOne;
    for (int k = 0; k < 3; ++k) {
      t.x_fixed[k] = cx + int32_t(r.below(uint32_t(2 * spread))) - spread;
      t.y_fixed[k] = cy + int32_t(r.below(uint32_t(2 * spread))) - spread;
    }
    if (trial % 5 == 1) t.y_fixed[1] = t.y_fixed[0];                               // a horizontal edge
    if (trial % 5 == 2) t.x_fixed[2] = t.x_fixed[1];                               // a vertical edge
    if (trial % 5 == 3) t.y_fixed[2] = t.y_fixed[0] + int32_t(r.below(3)) - 1;     // near-horizontal
    if (trial % 7 == 4) t.x_fixed[0] = (t.x_fixed[0] >> kFixedOrder) << kFixedOrder;  // on sample columns
    const int32_t tx = (cx >> kFixedOrder) & ~(kTileSize - 1), ty = (cy >> kFixedOrder) & ~(kTileSize - 1);
    const int32_t x0 = tx + int32_t(r.below(64)), y0 = ty + int32_t(r.below(64));
    const PixelRect rect{x0, y0, x0 + int32_t(r.below(uint32_t(tx + 64 - x0))),
                         y0 + int32_t(r.below(uint32_t(ty + 64 - y0)))};
    KernelJob job;
    if (setup_tile_edges(t, rect, job).fit != EdgeFit::Vector) continue;
    std::vector<int32_t> first(size_t(rect.y1 - rect.y0 + 1)), last(first.size());
    covered_columns_avx2(job, first.data(), last.data());
    for (int32_t py = rect.y0; py <= rect.y1; ++py) {
      int32_t lo = 1, hi = 0;  // the covered pixels of the row, one interval (a convex triangle)
      for (int32_t px = rect.x0; px <= rect.x1; ++px) {
        bool in = true;
        for (int i = 0; i < 3; ++i)
          in = in && int64_t(job.g_minus_1[i]) + int64_t(job.gx[i]) * (px - job.origin_x) +
                             int64_t(job.gy[i]) * (py - rect.y0) >= 0;
        if (!in) continue;
        ASSERT_TRUE(lo > hi || hi == px - 1) << "trial " << trial << " row " << py << " not one interval";
        if (lo > hi) lo = px;
        hi = px;
      }
      const size_t k = size_t(py - rect.y0);
      if (lo > hi) {
        ++empty_rows;
        ASSERT_GT(first[k], last[k]) << "trial " << trial << " row " << py << ": columns for an empty row";
      } else {
        ++covered_rows;
        ASSERT_EQ(first[k], lo) << "trial " << trial << " row " << py;
        ASSERT_EQ(last[k], hi) << "trial " << trial << " row " << py;
      }
    }
  }
  EXPECT_GT(covered_rows, 10000);
  EXPECT_GT(empty_rows, 1000);
}

// The vector tile kernels (AVX2, and AVX-512 sixteen pixels per step) write what the scalar kernel,
// the exact path's per-pixel functions, writes: random triangles from a few pixels to thousands wide
// over random rectangles of a tile (narrow, mid-size and all-in jobs, rows reaching the
// framebuffer's right edge), random stored depths, every depth format, compare op, writes on and
// off, depth clamp, polygon offset and FMA.
TEST(FastTileKernels, VectorKernelsWriteWhatTheScalarKernelWrites) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the vector kernels do not run";
  fast_test::Random r(29);
  constexpr int32_t kWidth = 200, kHeight = 192;  // the last tile column is 8 pixels wide
  int64_t written = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    FastTriangle t;
    const int32_t spreads[] = {3 * kFixedOne, 12 * kFixedOne, 60 * kFixedOne, 2000 * kFixedOne};
    const int32_t spread = spreads[trial % 4];
    const int32_t tx = int32_t(r.below(4)) * kTileSize, ty = int32_t(r.below(3)) * kTileSize;  // the tile
    const int32_t tile_x1 = std::min(tx + kTileSize, kWidth) - 1, tile_y1 = ty + kTileSize - 1;
    const int32_t cx = (tx + int32_t(r.below(uint32_t(tile_x1 - tx + 1)))) * kFixedOne,
                  cy = (ty + int32_t(r.below(kTileSize))) * kFixedOne;
    for (int k = 0; k < 3; ++k) {
      t.x_fixed[k] = cx + int32_t(r.below(uint32_t(2 * spread))) - spread;
      t.y_fixed[k] = cy + int32_t(r.below(uint32_t(2 * spread))) - spread;
    }
    const int64_t area = int64_t(t.x_fixed[0] - t.x_fixed[1]) * (t.y_fixed[2] - t.y_fixed[0]) -
                         int64_t(t.x_fixed[2] - t.x_fixed[0]) * (t.y_fixed[0] - t.y_fixed[1]);
    if (area < 0) std::swap(t.x_fixed[1], t.x_fixed[2]), std::swap(t.y_fixed[1], t.y_fixed[2]);  // §2.3
    // the triangle's box in the tile (as the fast path cuts it), or a random rectangle of the tile
    const auto [x_lo, x_hi] = std::minmax({t.x_fixed[0], t.x_fixed[1], t.x_fixed[2]});
    const auto [y_lo, y_hi] = std::minmax({t.y_fixed[0], t.y_fixed[1], t.y_fixed[2]});
    PixelRect rect{std::max(tx, (x_lo + kFixedOne - 1) >> kFixedOrder), std::max(ty, (y_lo + kFixedOne - 1) >> kFixedOrder),
                   std::min(tile_x1, (x_hi - 1) >> kFixedOrder), std::min(tile_y1, (y_hi - 1) >> kFixedOrder)};
    if (trial % 3 == 2 || rect.empty()) {
      const int32_t x0 = tx + int32_t(r.below(uint32_t(tile_x1 - tx + 1))), y0 = ty + int32_t(r.below(kTileSize));
      rect = PixelRect{x0, y0, x0 + int32_t(r.below(uint32_t(tile_x1 - x0 + 1))),
                       y0 + int32_t(r.below(uint32_t(tile_y1 - y0 + 1)))};
    }
    t.rect = rect;
    t.a0 = float(r.range(-0.3, 1.3));
    t.dzdx = float(r.range(-0.01, 0.01));
    t.dzdy = float(r.range(-0.01, 0.01));
    t.offset = r.chance(0.3) ? float(r.range(-0.05, 0.05)) : 0.0f;
    t.owner = 7 + uint32_t(trial);
    DepthTestState depth;
    depth.format = DepthFormat(trial % 4);
    depth.active = depth.format != DepthFormat::None;
    depth.op = depth.active ? CompareOp(r.below(8)) : CompareOp::Always;
    depth.write = depth.active && !r.chance(0.2);
    depth.range = DepthRange{r.chance(0.3), 0.2f, 0.7f};
    depth.fma = r.chance(0.5);
    KernelJob job;
    const EdgeSetup edges = setup_tile_edges(t, rect, job);
    if (edges.fit != EdgeFit::Vector) continue;
    job.a0 = t.a0, job.dzdx = t.dzdx, job.dzdy = t.dzdy, job.offset = t.offset;
    job.owner = t.owner;
    job.op = depth.op;
    job.all_in = edges.all_in;
    const KernelDepth kd{depth.active ? depth.format : DepthFormat::None, depth.op, depth.write, depth.range.clamp,
                         depth.range.zmin, depth.range.zmax, depth.fma};
    std::vector<uint32_t> stored(size_t(kWidth) * kHeight);
    for (uint32_t& v : stored) {
      const float z = float(r.range(0.0, 1.0));
      v = depth.format == DepthFormat::D32Sfloat  ? std::bit_cast<uint32_t>(z)
          : depth.format == DepthFormat::D16Unorm ? uint32_t(z * 65535.0f)
                                                  : uint32_t(z * 16777215.0f);
    }
    const std::vector<uint32_t> owners(stored.size(), kOwnerBackground);
    const auto target = [&](std::vector<uint32_t>& owner, std::vector<uint32_t>& z) {
      return TileTarget{owner.data(), depth.active ? z.data() : nullptr, kWidth, kHeight};
    };
    std::vector<uint32_t> owner_scalar = owners, depth_scalar = stored;
    const bool wrote = raster_scalar(t, rect, depth, target(owner_scalar, depth_scalar));
    written += wrote ? 1 : 0;
    std::vector<KernelFn> kernels{select_kernel_avx2(kd.format, job.op)};
    if (host_has_avx512()) kernels.push_back(select_kernel_avx512(kd.format, job.op));
    for (size_t k = 0; k < kernels.size(); ++k) {
      std::vector<uint32_t> owner_vector = owners, depth_vector = stored;
      EXPECT_EQ(kernels[k](job, kd, target(owner_vector, depth_vector)), wrote) << "trial " << trial << " kernel " << k;
      ASSERT_EQ(owner_vector, owner_scalar) << "trial " << trial << (k == 0 ? " avx2" : " avx512");
      ASSERT_EQ(depth_vector, depth_scalar) << "trial " << trial << (k == 0 ? " avx2" : " avx512");
    }
  }
  EXPECT_GT(written, 1800) << written;  // 2303 with this seed
}

// binned_tile_coverage answers for every pixel (and sample) of a tile what binned_covers answers,
// over random triangles with coordinates anywhere in int32 (llvmpipe's wrapping set-up), near the
// framebuffer and around it, single-sampled and 4x.
TEST(FastBinnedTiles, TileCoverageIsBinnedCoversPixelByPixel) {
  fast_test::Random r(29);
  const PixelRect framebuffer{0, 0, 299, 199};
  int64_t partial_tiles = 0, covered = 0, uncovered = 0;
  for (int trial = 0; trial < 1200; ++trial) {
    std::array<FixedPoint, 3> v;
    for (FixedPoint& p : v) {
      const bool huge = trial % 3 != 0 && r.chance(0.5);
      const auto coordinate = [&](int32_t extent) {
        return huge ? int32_t(uint32_t(r.below(UINT32_MAX))) : int32_t(r.below(uint32_t(2 * extent))) - extent / 4;
      };
      p = FixedPoint{Fixed24_8{coordinate(400 * kFixedOne)}, Fixed24_8{coordinate(300 * kFixedOne)}};
    }
    std::array<LpPlane, 8> planes{};
    const std::array<LpPlane, 3> edges = lp_edge_planes(v);
    std::copy(edges.begin(), edges.end(), planes.begin());
    const bool multisample = trial % 4 == 1;
    const BinnedTriangle t =
        bin_triangle(planes, 3, wrapped_triangle_bbox(v), framebuffer, framebuffer, multisample);
    std::array<uint64_t, kBinTile> rows;
    for (int32_t ty = 0; ty < t.tiles_y; ++ty) {
      for (int32_t tx = 0; tx < t.tiles_x; ++tx) {
        const uint32_t mask = t.tile_planes[size_t(ty) * size_t(t.tiles_x) + size_t(tx)];
        if (mask != 0 && mask != (uint32_t(1) << 31)) ++partial_tiles;
        for (uint32_t sample = 0; sample < (multisample ? 4u : 1u); ++sample) {
          binned_tile_coverage(t, tx, ty, sample, rows);
          for (int32_t j = 0; j < kBinTile; ++j) {
            for (int32_t i = 0; i < kBinTile; ++i) {
              const bool expected = binned_covers(t, tx * kBinTile + i, ty * kBinTile + j, sample);
              ASSERT_EQ(expected, ((rows[size_t(j)] >> i) & 1) != 0)
                  << "trial " << trial << " tile (" << tx << "," << ty << ") pixel (" << i << "," << j << ") sample "
                  << sample;
              ++(expected ? covered : uncovered);
            }
          }
        }
      }
    }
  }
  EXPECT_GT(partial_tiles, 200);
  EXPECT_GT(covered, 100000);
  EXPECT_GT(uncovered, 100000);
}

}  // namespace
}  // namespace rastercmp::cpu::fast
