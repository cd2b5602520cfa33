// Unit tests of the vector exact rows (exact_rows.hpp: rasterize_rows_avx2, and on AVX-512 hosts
// rasterize_box_avx512) against the exact rasterizer, primitive by primitive on the same targets,
// each primitive's visit cut as the tile rows and runs of tiles of several workers cut it.
#include <gtest/gtest.h>

#include <sys/mman.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/line_setup.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "cpu_raster/exact/render_targets.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/exact_rows.hpp"
#include "cpu_raster/fast/exact_rows_avx2.hpp"
#include "tests/test_fast_support.hpp"

namespace rastercmp::cpu::fast {
namespace {

// Renders `scene` draw by draw with the exact rasterizer and, on a copy of the same targets (their
// stored depths at random), with `rows` (rasterize_rows_avx2 unless given) on the pieces `cut(p)`
// makes of each primitive's visit, as the tile rows and runs of tiles of several workers cut it
// (rasterize_primitive_rows where it declines a piece); `seen(p, vector)` for each piece drawn. Both
// targets must hold the same owner and depth bytes after every draw.
bool vector_rows(const RasterPrimitive& p, int32_t y0, int32_t y1, const DepthTestState& depth,
                 RenderTargets& targets) {
  return rasterize_rows_avx2(p, y0, y1, depth, targets);
}

template <class Cut, class Seen, class Rows = decltype(&vector_rows)>
void expect_vector_rows_match(const Scene& scene, uint64_t seed, fast_test::Random& r, Cut cut, Seen seen,
                              Rows rows_kernel = &vector_rows) {
  const bool fma = seed % 3 != 0;
  const FrameContext frame = make_frame_context(scene, fma, {});
  RenderTargets exact = make_render_targets(scene);
  const uint32_t mask = depth_format_info(scene.depth_format).raw_mask;
  for (uint32_t& raw : exact.depth_raw) raw = r.chance(0.3) ? raw : r.below(1u << 24) & mask;
  if (is_float(scene.depth_format))
    for (uint32_t& raw : exact.depth_raw) raw = float_bits(float(r.unit()));
  RenderTargets vector = exact;
  for (uint32_t d = 0; d < scene.draws.size(); ++d) {
    const DepthTestState depth = make_depth_test_state(scene, scene.draws[d], frame.viewport, fma);
    run_front_end(frame, d, [&](const PrimitiveOutcome& outcome) {
      if (!outcome.rasterized()) return;
      const RasterPrimitive& p = outcome.raster;
      rasterize_primitive(p, depth, exact, WorkSkips{});
      if (p.visit.empty()) return;
      for (const PixelRect& piece : cut(p)) {
        if (piece.empty()) continue;
        RasterPrimitive band = p;
        band.visit = piece;
        const bool drawn = rows_kernel(band, piece.y0, piece.y1, depth, vector);
        if (!drawn) rasterize_primitive_rows(band, depth, vector, true);
        seen(p, drawn);
      }
    });
    ASSERT_EQ(exact.owner, vector.owner) << "seed " << seed << " draw " << d;
    ASSERT_EQ(exact.depth_raw, vector.depth_raw) << "seed " << seed << " draw " << d;
  }
}

// A visit's rows split at a random row, as the tile rows of two workers split them (the first piece
// empty when the split is its first row).
std::array<PixelRect, 2> split_at_random_row(const PixelRect& visit, fast_test::Random& r) {
  const int32_t split = visit.y0 + int32_t(r.below(uint32_t(visit.y1 - visit.y0 + 1)));
  return {PixelRect{visit.x0, visit.y0, visit.x1, split - 1}, PixelRect{visit.x0, split, visit.x1, visit.y1}};
}

// rasterize_rows_avx2 (exact_rows.hpp) against the exact rasterizer, primitive by primitive on the
// same targets: random scenes of lines (every mode, widths 0.5-6 px, non-integer too) and triangles,
// half of them in 4x frames (per-sample triangles and rectangular lines, pixel-centre Bresenham
// lines), every depth format and compare op, writes, clamp, bias, scissors and viewports that cut
// primitives, stored depths at random, each primitive's rows split at a random row as the tile rows
// split them. On AVX-512 hosts half of the 1x frames take the scattered writes (avx512_writes), the
// others, and every frame on other hosts, the blended ones.
TEST(FastExactRows, VectorRowsWriteWhatTheExactRasterizerWrites) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "the host runs no AVX2";
  uint64_t vector_primitives = 0, lines = 0, per_sample = 0, scattered_lines = 0;
  for (uint64_t seed = 1; seed <= 160; ++seed) {
    fast_test::Random r(seed * 7919);
    fast_test::RandomSceneSpec spec;
    spec.max_primitives = 60;
    Scene scene = fast_test::random_scene(seed, spec);
    if (seed % 2 == 0) scene.samples = 4;
    for (Draw& draw : scene.draws) {
      if (r.chance(0.5)) draw.state.line_width = float(r.range(0.5, 6.0));
      if (r.chance(0.15)) draw.state.line_mode = LineMode::RectangularSmooth;
    }
    const auto rows = [&r](const RasterPrimitive& p) { return split_at_random_row(p.visit, r); };
    const bool avx512_writes = host_has_avx512() && seed % 4 == 1;
    const auto kernel = [avx512_writes](const RasterPrimitive& p, int32_t y0, int32_t y1, const DepthTestState& depth,
                                        RenderTargets& targets) {
      return rasterize_rows_avx2(p, y0, y1, depth, targets, avx512_writes);
    };
    expect_vector_rows_match(
        scene, seed, r, rows,
        [&](const RasterPrimitive& p, bool vector) {
          vector_primitives += vector ? 1 : 0;
          lines += vector && p.is_line ? 1 : 0;
          per_sample += vector && p.per_sample ? 1 : 0;
          scattered_lines += vector && p.is_line && avx512_writes ? 1 : 0;
        },
        kernel);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(vector_primitives, 2000u);
  EXPECT_GT(lines, 500u);
  EXPECT_GT(per_sample, 500u);
  if (host_has_avx512()) {
    EXPECT_GT(scattered_lines, 200u);
  }
}

// Every attachment page but those of a piece's own rows in its half of the frame (or, with
// whole_rows, in the whole frame) made read-only (prot PROT_READ), or all made writable again
// (PROT_READ | PROT_WRITE). Each half row is whole pages: the frame is 2048 px wide and its buffers
// start on a page (PixelAllocator, colour 0).
void protect_outside_piece(RenderTargets& t, const PixelRect& piece, int prot, bool whole_rows = false) {
  const size_t half = size_t(t.width / 2) * t.samples * sizeof(uint32_t);
  const size_t side = piece.x0 >= int32_t(t.width / 2) ? 1 : 0;
  for (PixelBuffer* buffer : {&t.owner, &t.depth_raw}) {
    if (buffer->empty()) continue;
    char* base = reinterpret_cast<char*>(buffer->data());
    ASSERT_EQ(reinterpret_cast<uintptr_t>(base) % 4096, 0u);
    ASSERT_EQ(mprotect(base, buffer->size() * sizeof(uint32_t), prot), 0);
    if (prot != PROT_READ) continue;
    for (int32_t y = piece.y0; y <= piece.y1; ++y) {
      if (whole_rows)
        ASSERT_EQ(mprotect(base + size_t(y) * 2 * half, 2 * half, PROT_READ | PROT_WRITE), 0);
      else
        ASSERT_EQ(mprotect(base + (size_t(y) * 2 + side) * half, half, PROT_READ | PROT_WRITE), 0);
    }
  }
}

// Lines across the middle of frames 2048 px wide and up to their right edge: steep ones near the
// middle, shallow ones across the frame (every mode, widths 0.5-5 px, 1x and 4x, the random
// scenes' depth states).
Scene lines_across_wide_frame(uint64_t seed, fast_test::Random& r) {
  Scene scene = fast_test::random_scene(seed);
  scene.width = 2048;
  scene.height = 24 + r.below(24);
  scene.samples = seed % 4 == 0 ? 4 : 1;
  scene.scissor.reset();
  for (Draw& draw : scene.draws) {
    draw.topology = Topology::LineList;
    draw.indices.clear();
    draw.positions_clip.clear();
    draw.state.line_width = r.chance(0.5) ? 1.0f : float(r.range(0.5, 5.0));
    for (uint32_t k = 0; k < 80; ++k) {
      const double reach = k % 2 == 0 ? 0.02 : 1.1;  // steep near the middle, or shallow across it
      const float z = float(r.range(0.0, 1.0));
      draw.positions_clip.emplace_back(float(r.range(-reach, reach)), float(r.range(-1.2, 1.2)), z, 1.0f);
      draw.positions_clip.emplace_back(float(r.range(-reach, reach)), float(r.range(-1.2, 1.2)), z, 1.0f);
    }
  }
  return scene;
}

// rasterize_rows_avx2 on a piece with every page outside it read-only while it draws
// (protect_outside_piece): outside the piece's rows in its half of the frame, or with whole_rows
// (owned_row_end the frame's last column) outside its rows.
auto guarded_rows(bool avx512_writes, bool whole_rows) {
  return [avx512_writes, whole_rows](const RasterPrimitive& p, int32_t y0, int32_t y1, const DepthTestState& depth,
                                     RenderTargets& targets) {
    protect_outside_piece(targets, p.visit, PROT_READ, whole_rows);
    const bool drawn =
        rasterize_rows_avx2(p, y0, y1, depth, targets, avx512_writes, whole_rows ? int32_t(targets.width) - 1 : -1);
    protect_outside_piece(targets, p.visit, PROT_READ | PROT_WRITE, whole_rows);
    return drawn;
  };
}

// rasterize_rows_avx2 writes nothing outside the rows and columns of the visit it is given, which
// the workers' shared rows rely on: its steps that write every lane back (the blended gathered
// steps, the pairs, a row's whole eight columns) leave out any column past the visit, as the masked
// ones do. Lines across the middle of frames 2048 px wide (steep ones near it, shallow ones across
// it; every mode, widths 0.5-5 px, 1x and 4x, the random scenes' depth states) have their visits cut
// at the middle column, and every page outside a piece's rows in its half is read-only while it is
// drawn: a write there stops the test with SIGSEGV. The bytes are also the exact rasterizer's.
TEST(FastExactRows, VectorRowsWriteNothingOutsideTheirVisit) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the vector exact rows do not run";
  uint64_t pieces = 0, whole_steps = 0;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    fast_test::Random r(seed * 6151);
    const Scene scene = lines_across_wide_frame(seed, r);
    const int32_t middle = int32_t(scene.width / 2);
    const auto halves = [middle](const RasterPrimitive& p) {
      return std::array<PixelRect, 2>{PixelRect{p.visit.x0, p.visit.y0, std::min(p.visit.x1, middle - 1), p.visit.y1},
                                      PixelRect{std::max(p.visit.x0, middle), p.visit.y0, p.visit.x1, p.visit.y1}};
    };
    const bool avx512_writes = host_has_avx512() && seed % 2 == 1;
    const auto guarded = guarded_rows(avx512_writes, false);
    expect_vector_rows_match(
        scene, seed, r, halves,
        [&](const RasterPrimitive& p, bool vector) {
          pieces += vector ? 1 : 0;
          whole_steps += vector && p.visit.x1 - p.visit.x0 >= 16 ? 1 : 0;
        },
        guarded);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(pieces, 2000u);
  EXPECT_GT(whole_steps, 500u);
}

// With owned_row_end the frame's last column (every column of the rows the caller's, as a worker's
// whole tile rows), a step may store back pixels of its rows beside the visit, and
// rasterize_rows_avx2 writes nothing outside those rows: the lines above, each primitive's rows
// split at a random row, every page outside a piece's rows read-only while it is drawn. The bytes
// are also the exact rasterizer's.
TEST(FastExactRows, VectorRowsWithWholeRowsWriteNothingOutsideTheirRows) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the vector exact rows do not run";
  uint64_t pieces = 0;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    fast_test::Random r(seed * 4217);
    const Scene scene = lines_across_wide_frame(seed, r);
    const auto rows = [&r](const RasterPrimitive& p) { return split_at_random_row(p.visit, r); };
    const bool avx512_writes = host_has_avx512() && seed % 2 == 1;
    const auto guarded = guarded_rows(avx512_writes, true);
    expect_vector_rows_match(
        scene, seed, r, rows, [&](const RasterPrimitive&, bool vector) { pieces += vector ? 1 : 0; }, guarded);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(pieces, 2000u);
}

// The box kernels' small per-sample primitives (sample_box_rows, exact_rows_4x_avx2.cpp, through
// rasterize_rows_avx2; and on AVX-512 hosts box16, exact_rows_avx512.cpp, through
// rasterize_box_avx512) against the exact rasterizer: triangles of 0.3-40 px (and some far larger)
// in 4x frames of odd and even widths (a row's first step starts up to three columns before the
// visit), with scissors and viewports that cut them, every depth format and compare op, writes,
// clamp and bias, each primitive's visit cut into runs of columns and rows as the tiles of several
// workers cut it.
void expect_small_per_sample_triangles_match(bool avx512) {
  uint64_t small = 0, boxed = 0;
  const auto box_first = [&boxed](const RasterPrimitive& p, int32_t y0, int32_t y1, const DepthTestState& depth,
                                  RenderTargets& targets) {
    if (rasterize_box_avx512(p, y0, y1, depth, targets)) {
      ++boxed;
      return true;
    }
    return rasterize_rows_avx2(p, y0, y1, depth, targets);
  };
  for (uint64_t seed = 1; seed <= 120; ++seed) {
    fast_test::Random r(seed * 104729);
    Scene scene = fast_test::random_scene(seed, fast_test::RandomSceneSpec{true, false, 90, 40});
    scene.samples = 4;
    if (seed % 4 == 0)  // a small scissor: small visits of the huge triangles below
      scene.scissor = Rect2D{int32_t(r.below(scene.width / 2)), int32_t(r.below(scene.height / 2)), 1 + r.below(20),
                             1 + r.below(12)};
    if (seed % 3 == 1)  // a viewport far larger than the frame: edges of thousands of pixels
      scene.viewport = Viewport{-4000.0f, -4000.0f, 8192.0f, 8192.0f, 0.0f, 1.0f};
    for (Draw& draw : scene.draws) {
      draw.topology = Topology::TriangleList;
      draw.indices.clear();
      draw.positions_clip.clear();
      // in clip units: a few pixels, up to 40, or huge (edges whose values leave int32 across a
      // small visit cut by a scissor: the box kernel declines them)
      const double size = r.chance(0.1) ? 60.0 : r.chance(0.5) ? 0.05 : 0.4;
      for (uint32_t t = 0, n = 6 + r.below(60); t < n; ++t) {
        const double cx = r.range(-1.1, 1.1), cy = r.range(-1.1, 1.1), cz = r.range(-0.1, 1.1);
        for (int k = 0; k < 3; ++k)
          draw.positions_clip.emplace_back(float(cx + r.range(-size, size)), float(cy + r.range(-size, size)),
                                           float(cz + r.range(-0.2, 0.2)), 1.0f);
      }
    }
    const auto quarters = [&r](const RasterPrimitive& p) {
      const PixelRect& v = p.visit;
      const int32_t y = v.y0 + int32_t(r.below(uint32_t(v.y1 - v.y0 + 1)));
      const int32_t x = v.x0 + int32_t(r.below(uint32_t(v.x1 - v.x0 + 1)));
      return std::array<PixelRect, 4>{PixelRect{v.x0, v.y0, x - 1, y - 1}, PixelRect{x, v.y0, v.x1, y - 1},
                                      PixelRect{v.x0, y, x - 1, v.y1}, PixelRect{x, y, v.x1, v.y1}};
    };
    const auto seen = [&](const RasterPrimitive& p, bool) { small += p.visit.x1 - p.visit.x0 < 24 ? 1 : 0; };
    if (avx512)
      expect_vector_rows_match(scene, seed, r, quarters, seen, box_first);
    else
      expect_vector_rows_match(scene, seed, r, quarters, seen);
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(small, 1500u);
  if (avx512) {
    EXPECT_GT(boxed, 1500u);
  }
}

// A random int64 of about `bits` bits, either sign; one time in five within two of a bound
// (+-2^bits), where the checks of init_plane_rows turn.
int64_t near_bits(fast_test::Random& r, uint32_t bits) {
  const int64_t edge = int64_t(1) << bits, sign = r.chance(0.5) ? -1 : 1;
  if (r.chance(0.2)) return sign * (edge + int64_t(r.below(5)) - 2);
  return sign * int64_t(r.unit() * double(edge));
}

// The four-plane rows (init_four_plane_rows, the way init_plane_rows takes for a line of one
// sample) against the plane by plane ones (init_plane_rows_each): the same verdict through
// init_plane_rows, and wherever the four-plane way takes a primitive, every value bit for bit (the
// places, each plane's first value, row and column steps, reciprocal). The planes at random, their
// deltas, constants, visit columns and rows from small to past every bound (2^30 a delta, 2^20 a
// column, 2^51 a value, int32 a row), flat planes and per-sample primitives among them.
TEST(FastExactRows, FourPlaneRowsAreThePlaneByPlaneRows) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the vector exact rows do not run";
  fast_test::Random r(20261130);
  uint64_t taken = 0, declined_agreeing = 0, refused = 0;
  for (int n = 0; n < 100000; ++n) {
    RasterPrimitive p;
    p.per_sample = r.chance(0.2);
    for (uint32_t i = 0; i < 4; ++i) {
      EdgePlane plane;
      plane.dcdx = r.chance(0.15) ? 0 : near_bits(r, r.below(32));
      plane.dcdy = r.chance(0.15) ? 0 : near_bits(r, r.below(32));
      plane.c = near_bits(r, r.chance(0.5) ? r.below(24) : 40 + r.below(14));
      p.planes.push(plane);
    }
    const int32_t x0 = int32_t(near_bits(r, r.chance(0.8) ? r.below(12) : 19 + r.below(3)));
    p.visit = PixelRect{x0, 0, x0 + int32_t(r.below(300)), 0};
    const int32_t y0 = int32_t(near_bits(r, r.chance(0.8) ? r.below(12) : 22 + r.below(2)));
    const int32_t y1 = y0 + int32_t(r.below(r.chance(0.9) ? 300 : 1u << 24));
    PlaneRows each, four, chosen;
    const bool each_ok = init_plane_rows_each(each, p, 1, y0, y1);
    ASSERT_EQ(init_plane_rows(chosen, p, 1, y0, y1), each_ok) << "primitive " << n;
    if (!init_four_plane_rows(four, p, y0, y1)) {
      (each_ok ? declined_agreeing : refused) += 1;
      continue;
    }
    ++taken;
    ASSERT_TRUE(each_ok) << "primitive " << n;
    ASSERT_EQ(four.lower, each.lower);
    ASSERT_EQ(four.upper, each.upper);
    ASSERT_EQ(four.count, each.count);
    for (uint32_t e = 0; e < 4; ++e) {
      EXPECT_EQ(std::memcmp(&four.first[0][e], &each.first[0][e], sizeof(double)), 0) << "primitive " << n;
      EXPECT_EQ(std::memcmp(&four.dy[e], &each.dy[e], sizeof(double)), 0) << "primitive " << n;
      EXPECT_EQ(std::memcmp(&four.step[e], &each.step[e], sizeof(__m256d)), 0) << "primitive " << n;
      EXPECT_EQ(std::memcmp(&four.gx[e], &each.gx[e], sizeof(__m256d)), 0) << "primitive " << n;
      EXPECT_EQ(std::memcmp(&four.inv[e], &each.inv[e], sizeof(__m256d)), 0) << "primitive " << n;
    }
  }
  std::printf("four-plane rows: %llu taken, %llu declined where plane by plane takes them, %llu refused by both\n",
              (unsigned long long)taken, (unsigned long long)declined_agreeing, (unsigned long long)refused);
  EXPECT_GT(taken, 10000u);
  EXPECT_GT(refused, 10000u);
}

// A line's middle rows (parallelogram_middle, where thin_rows takes a step's columns from the long
// edges alone): on lines from setup_line (rectangular and Bresenham, widths 0.5-6 px, 1-200 px
// long, every angle, ends anywhere in a pixel), in every middle row of the visit every sample
// from two columns before the visit to two after that passes both long edges passes both caps; the
// places name the long edges (the lower one bounds below, the upper one above, with their planes'
// row steps). A quad that is not a parallelogram (one corner moved, its planes made from its
// corners) has no middle.
TEST(FastExactRows, ParallelogramMiddleRowsNeedNoCaps) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the vector exact rows do not run";
  fast_test::Random r(20261201);
  RasterState state;
  SetupContext ctx;
  ctx.framebuffer = PixelRect{0, 0, 1023, 1023};
  ctx.region = ctx.framebuffer;
  ctx.state = &state;
  ctx.depth_format = DepthFormat::D32Sfloat;
  uint64_t middles = 0, rows_checked = 0, samples_checked = 0, trapezoids = 0;
  for (int n = 0; n < 4000; ++n) {
    state.line_mode = r.chance(0.2) ? LineMode::Bresenham : LineMode::Default;
    state.line_width = r.chance(0.5) ? 1.0f : float(r.range(0.5, 6.0));
    const double length = r.range(1.0, 200.0), angle = r.range(0.0, 6.283185307179586);
    const double cx = r.range(200.0, 800.0), cy = r.range(200.0, 800.0);
    const std::array<WindowVertex, 2> window{
        WindowVertex{float(cx), float(cy), 0.5f},
        WindowVertex{float(cx + length * std::cos(angle)), float(cy + length * std::sin(angle)), 0.5f}};
    const LineSetup setup = setup_line(window, 1, ctx);
    if (setup.fate != SetupFate::Rasterized || setup.raster.binned) continue;
    const RasterPrimitive& p = setup.raster;
    const int32_t y0 = p.visit.y0, y1 = p.visit.y1;
    PlaneRows rows;
    if (!init_plane_rows(rows, p, 1, y0, y1)) continue;
    const ParallelogramMiddle middle = parallelogram_middle(p, rows);
    if (middle.first_row <= middle.last_row) {
      ++middles;
      const EdgePlane* e = p.planes.plane.data();
      const uint32_t long_below = e[0].dcdx < 0 ? 0 : 2;
      ASSERT_LT(middle.lower, rows.lower) << "line " << n;
      ASSERT_GE(middle.upper, rows.lower) << "line " << n;
      ASSERT_LT(middle.upper, rows.upper) << "line " << n;
      ASSERT_EQ(rows.dy[middle.lower], double(e[long_below].dcdy * kFixedOne)) << "line " << n;
      ASSERT_EQ(rows.dy[middle.upper], double(e[2 - long_below].dcdy * kFixedOne)) << "line " << n;
      for (int32_t py = std::max(middle.first_row, y0); py <= std::min(middle.last_row, y1); ++py) {
        ++rows_checked;
        for (int32_t px = p.visit.x0 - 2; px <= p.visit.x1 + 2; ++px) {
          const int64_t x = int64_t(px) * kFixedOne, y = int64_t(py) * kFixedOne;
          if (edge_value(e[0], x, y) <= 0 || edge_value(e[2], x, y) <= 0) continue;
          ++samples_checked;
          ASSERT_GT(edge_value(e[1], x, y), 0) << "line " << n << " row " << py << " column " << px;
          ASSERT_GT(edge_value(e[3], x, y), 0) << "line " << n << " row " << py << " column " << px;
        }
      }
    }
    RasterPrimitive trapezoid = p;  // corner 2 a pixel to the right, the planes its corners'
    trapezoid.vertex_fixed[2].x.raw += kFixedOne;
    trapezoid.planes.count = 0;
    for (uint32_t i = 0; i < 4; ++i)
      trapezoid.planes.push(
          make_edge(trapezoid.vertex_fixed[i], trapezoid.vertex_fixed[(i + 1) % 4], ctx.methods.tie_break));
    PlaneRows trapezoid_rows;
    if (!init_plane_rows(trapezoid_rows, trapezoid, 1, y0, y1)) continue;
    ++trapezoids;
    const ParallelogramMiddle none = parallelogram_middle(trapezoid, trapezoid_rows);
    ASSERT_GT(none.first_row, none.last_row) << "line " << n;
  }
  std::printf("parallelogram middles: %llu lines, %llu rows, %llu samples inside the long edges; %llu trapezoids\n",
              (unsigned long long)middles, (unsigned long long)rows_checked, (unsigned long long)samples_checked,
              (unsigned long long)trapezoids);
  EXPECT_GT(middles, 2000u);
  EXPECT_GT(samples_checked, 100000u);
  EXPECT_GT(trapezoids, 2000u);
}

TEST(FastExactRows, SmallPerSampleTrianglesWriteWhatTheExactRasterizerWrites) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the box kernels never run here";
  expect_small_per_sample_triangles_match(false);
}

TEST(FastExactRows, SixteenLaneBoxWritesWhatTheExactRasterizerWrites) {
  if (!host_has_avx512()) GTEST_SKIP() << "host without AVX-512: the sixteen-lane box kernel never runs here";
  expect_small_per_sample_triangles_match(true);
}

}  // namespace
}  // namespace rastercmp::cpu::fast
