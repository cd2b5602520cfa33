// Unit tests of the fast path's phases before the walks, each against the exact path's own
// functions or a brute-force answer: the per-vertex pass (scalar, AVX2, AVX-512), the chunk flags
// from its compact rows, the list reach phase's packed tile rows, the block-row phase (its
// sixteen-block shortcut, the run skip, blocks left out), the row balance (whole rows, by pace,
// runs of tiles).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/clip_vertex.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"
#include "cpu_raster/exact/fixed_point.hpp"
#include "cpu_raster/fast/block_rows.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/exact_reach.hpp"
#include "cpu_raster/fast/fast_frame.hpp"
#include "cpu_raster/fast/fast_vertices.hpp"
#include "cpu_raster/fast/row_balance.hpp"
#include "cpu_raster/fast/trailing_check.hpp"
#include "tests/test_fast_support.hpp"

namespace rastercmp::cpu::fast {
namespace {

// Positions of every kind the vertex pass meets: random ones inside and outside the clip volume,
// then NaN, an infinity, w = 0, one beyond the snap's range, and a few plain ones (the last seven).
std::vector<glm::vec4> awkward_positions() {
  fast_test::Random r(7);
  std::vector<glm::vec4> p;
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < 997; ++i)
    p.emplace_back(float(r.range(-3, 3)), float(r.range(-3, 3)), float(r.range(-1, 2)), float(r.range(-0.5, 3)));
  for (const glm::vec4& v :
       {glm::vec4(nan, 0, 0, 1), glm::vec4(0, inf, 0, 1), glm::vec4(0, 0, 0, 0), glm::vec4(1e30f, 0, 0, 1),
        glm::vec4(0.25f, -0.5f, 0.5f, 1), glm::vec4(1, 1, 1, 1), glm::vec4(-1, -1, 0, 1)})
    p.push_back(v);
  return p;
}

// The same vertex, bit for bit.
void expect_same_vertex(const FastVertex& a, const FastVertex& b, size_t k) {
  EXPECT_EQ(a.flags, b.flags) << "position " << k;
  EXPECT_EQ(std::bit_cast<uint32_t>(a.x), std::bit_cast<uint32_t>(b.x)) << "position " << k;
  EXPECT_EQ(std::bit_cast<uint32_t>(a.y), std::bit_cast<uint32_t>(b.y)) << "position " << k;
  EXPECT_EQ(std::bit_cast<uint32_t>(a.z), std::bit_cast<uint32_t>(b.z)) << "position " << k;
}

TEST(FastVertices, ScalarPassIsTheExactPathsPerVertexWork) {
  const std::vector<glm::vec4> positions = awkward_positions();
  const ViewportTransform viewport = make_viewport_transform(Viewport{3.5f, -2, 301, 177, 0.25f, 0.75f});
  for (const bool fma : {true, false}) {
    std::vector<FastVertex> out(positions.size());
    std::vector<int16_t> rows(positions.size() + 8);
    transform_vertices_scalar(VertexJob{positions.data(), viewport, fma, true}, 0, positions.size(), out.data(),
                              rows.data());
    for (size_t k = 0; k < positions.size(); ++k) {
      const ClipVertex exact = make_clip_vertex(positions[k], viewport, true, fma);
      EXPECT_EQ(out[k].flags & kVertexClipBits, exact.clip_mask);
      EXPECT_EQ(std::bit_cast<uint32_t>(out[k].x), std::bit_cast<uint32_t>(exact.window.x));
      const auto x = snap_vertex(exact.window.x, 0.5f, SnapRounding::NearestEven);
      const auto y = snap_vertex(exact.window.y, 0.5f, SnapRounding::NearestEven);
      EXPECT_EQ((out[k].flags & kVertexSnapFailed) != 0, !x || !y);
      if (x && y) {  // the snap the set-up recomputes from the stored window position
        EXPECT_EQ(snap_fixed(out[k].x), x->raw) << "position " << k;
        EXPECT_EQ(snap_fixed(out[k].y), y->raw) << "position " << k;
      }
      // the tile row of a vertex that needs neither clipping nor a failed snap, else unknown
      EXPECT_EQ(rows[k], out[k].flags ? unknown_row(out[k].flags) : int16_t(y ? y->raw >> 14 : 0));
    }
  }
}

using VertexPass = uint32_t (*)(const VertexJob&, size_t, size_t, FastVertex*, int16_t*);

// A vector pass gives every vertex of awkward_positions (NaN, infinities, w = 0, out of the snap's
// range, on the clip planes) the scalar pass's window position, flags and tile row, from an
// unaligned start and with a scalar head and tail. The special positions (the list's last seven)
// are moved to 23-29: inside the vector steps of both widths.
void expect_pass_equals_scalar(VertexPass pass) {
  std::vector<glm::vec4> positions = awkward_positions();
  std::rotate(positions.begin(), positions.end() - 30, positions.end());
  const ViewportTransform viewport = make_viewport_transform(Viewport{0, 0, 1024, -768, 0, 1});
  for (const bool depth_clip : {true, false}) {
    for (const bool fma : {true, false}) {
      const VertexJob job{positions.data(), viewport, fma, depth_clip};
      std::vector<FastVertex> scalar(positions.size()), vector(positions.size());
      std::vector<int16_t> scalar_rows(positions.size() + 8), vector_rows(positions.size() + 8);
      const uint32_t scalar_flags =
          transform_vertices_scalar(job, 0, positions.size(), scalar.data(), scalar_rows.data());
      // an unaligned start, then a scalar tail
      uint32_t vector_flags = pass(job, 3, positions.size(), vector.data(), vector_rows.data());
      vector_flags |= transform_vertices_scalar(job, 0, 3, vector.data(), vector_rows.data());
      EXPECT_EQ(scalar_flags, vector_flags);
      for (size_t k = 0; k < positions.size(); ++k) {
        expect_same_vertex(scalar[k], vector[k], k);
        EXPECT_EQ(scalar_rows[k], vector_rows[k]) << "position " << k;
      }
    }
  }
}

TEST(FastVertices, Avx2PassEqualsScalarPass) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: only the scalar pass runs here";
  expect_pass_equals_scalar(transform_vertices_avx2);
}

TEST(FastVertices, Avx512PassEqualsScalarPass) {
  if (!host_has_avx512()) GTEST_SKIP() << "host without AVX-512: the AVX-512 pass never runs here";
  expect_pass_equals_scalar(transform_vertices_avx512);
}

// The chunk flags from the vertex phase's compact rows (transformed_pipelined_chunks) are the
// exact path's (pipelined_chunks_by with clip_test.hpp's mask) for every topology, with and
// without indices: chunks of several sizes, a few clipped vertices at random places (a chunk's
// flag then hangs on one vertex), indices past the positions (counted as unclipped), positions
// with w = 0 at the origin (no clip bit, a failed snap); also chunk by chunk, as the chunk-flag
// phase's tasks scan them.
TEST(FastChunkFlags, CompactRowsGiveTheExactPathsChunkFlags) {
  fast_test::Random r(7);
  const ViewportTransform viewport = make_viewport_transform(Viewport{0, 0, 640, 480, 0, 1});
  for (const Topology topology : {Topology::PointList, Topology::LineList, Topology::LineStrip, Topology::TriangleList,
                                  Topology::TriangleStrip, Topology::TriangleFan}) {
    for (const bool indexed : {false, true}) {
      for (const uint32_t vertices : {1u, 5u, 4000u, 9000u}) {
        Scene scene;
        Draw draw;
        draw.topology = topology;
        for (uint32_t k = 0; k < vertices; ++k) {
          // about one vertex in 500 clipped, and position 3, where an index past the positions
          // would land if it wrapped; now and then (0, 0, 0, 0): no clip bit, and its snap fails
          if (k % 1000 == 7) {
            draw.positions_clip.emplace_back(0.0f, 0.0f, 0.0f, 0.0f);
            continue;
          }
          const bool outside = k == 3 || r.unit() < 0.002;  // then past the right plane
          draw.positions_clip.emplace_back(outside ? 2.0f : float(r.range(-0.9, 0.9)), float(r.range(-0.9, 0.9)),
                                           float(r.range(0.1, 0.9)), 1.0f);
        }
        if (indexed)
          for (uint32_t k = 0; k < vertices; ++k)
            draw.indices.push_back(r.unit() < 0.001 ? vertices + 3 : r.below(vertices));
        scene.draws.push_back(draw);
        std::vector<FastVertex> out(vertices);
        std::vector<int16_t> rows(vertices + 8);
        transform_vertices_scalar(VertexJob{draw.positions_clip.data(), viewport, true, true}, 0, vertices, out.data(),
                                  rows.data());
        FastFrame frame;
        frame.scene = &scene;
        frame.draws.resize(1);
        frame.draws[0].vertices = out.data();
        frame.draws[0].tile_rows = rows.data();
        const std::vector<bool> exact = pipelined_chunks_by(draw, [&draw](uint32_t position) {
          return position < draw.positions_clip.size() && clip_mask(draw.positions_clip[position], true) != 0;
        });
        SCOPED_TRACE(std::string(to_string(topology)) + (indexed ? " indexed " : " ") + std::to_string(vertices));
        EXPECT_EQ(transformed_pipelined_chunks(frame, 0), exact);
        // the chunk-flag phase's tasks: runs of three chunks, each flag written once
        std::vector<uint8_t> ranged(exact.size(), 2);
        for (uint32_t c = 0; c < exact.size(); c += 3)
          transformed_pipelined_chunk_range(frame, 0, c, std::min(uint32_t(exact.size()), c + 3), ranged.data());
        for (size_t c = 0; c < exact.size(); ++c) EXPECT_EQ(ranged[c], exact[c] ? 1 : 0) << "chunk " << c;
        if (vertices == 9000) {
          EXPECT_NE(std::count(exact.begin(), exact.end(), true), 0);
        }
      }
    }
  }
}

// The reach phase's packed tile rows (exact_reach.hpp) answer as the pixel rows they came from:
// for spans in, across, above and below the frame (far beyond it too), every run of tile rows a
// worker may own meets the packed rows exactly when it meets the span's, and both say "no row of
// the frame" alike; an unsettled span stays unsettled.
TEST(FastListReach, PackedTileRowsGiveTheSameAnswers) {
  fast_test::Random r(11);
  EXPECT_EQ(pack_tile_rows(RowSpan{}, 16), kReachUnsettled);
  for (const int32_t tiles_y : {1, 5, 16, 256}) {
    for (int n = 0; n < 4000; ++n) {
      const int32_t reach = int32_t(r.below(4)) == 0 ? 20000000 : 64 * (tiles_y + 3);
      const int32_t lo = int32_t(r.range(-reach, reach)), hi = lo + int32_t(r.below(n % 2 ? 200 : 100000));
      const RowSpan span{true, lo, hi};
      const uint32_t packed = pack_tile_rows(span, tiles_y);
      ASSERT_NE(packed, kReachUnsettled);
      const auto [tile_lo, tile_hi] = unpack_tile_rows(packed);
      const int32_t exact_lo = lo >> kTileOrder, exact_hi = hi >> kTileOrder;
      for (int32_t first = 0; first < tiles_y; ++first) {
        for (int32_t last = first; last < std::min(tiles_y, first + 3); ++last) {
          const bool meets = std::max(exact_lo, first) <= std::min(exact_hi, last);
          EXPECT_EQ(std::max(tile_lo, first) <= std::min(tile_hi, last), meets) << lo << ".." << hi;
        }
      }
      EXPECT_EQ(tile_hi < 0 || tile_lo >= tiles_y, exact_hi < 0 || exact_lo >= tiles_y) << lo << ".." << hi;
    }
  }
}

// The reach phase's eight-wide lines (line_list_reach_avx2) against the scalar row_span_of and
// pack_tile_rows, line by line: corners anywhere in and far beyond a frame, on tile borders, at
// +-0, infinite, NaN, past 1e7 and spanning past 32000 px, with clip bits and failed snaps (not
// clip bits), margins of thin and wide lines, tasks of any start and length (the last lines one by
// one), and lines at the bounds (a span of exactly 32000 px, y across +-1e7). Six mutations of the
// code (the span's bound by >, the clamp at 0, the flags' snap bit taken for a clip bit, y_lo's
// bound on y_hi, x's span left out, the transpose's lanes of the second corner swapped) each fail
// it.
TEST(FastListReach, EightLinesAtOnceGiveTheScalarAnswers) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the reach phase takes the lines one by one";
  fast_test::Random r(5);
  const auto coordinate = [&r](float extent) {
    switch (r.below(12)) {
      case 0: return std::numeric_limits<float>::infinity() * (r.chance(0.5) ? 1.0f : -1.0f);
      case 1: return std::numeric_limits<float>::quiet_NaN();
      case 2: return r.chance(0.5) ? 0.0f : -0.0f;
      case 3: return float(r.range(-3e7, 3e7));
      case 4: return float(64 * int(r.below(20)) - 64) + (r.chance(0.5) ? 0.0f : float(r.range(-3.5, 3.5)));
      default: return float(r.range(-0.2 * extent, 1.2 * extent));
    }
  };
  for (int trial = 0; trial < 400; ++trial) {
    const int32_t tiles_y = int32_t(1 + r.below(20));
    const float extent = float(64 * tiles_y);
    const uint32_t lines = 1 + r.below(300);
    std::vector<FastVertex> vertices(2 * size_t(lines));
    for (FastVertex& v : vertices) {
      const bool near = r.chance(0.9);
      v.x = near ? float(r.range(0, extent)) : coordinate(extent);
      v.y = near ? float(r.range(-0.1 * extent, 1.1 * extent)) : coordinate(extent);
      v.z = float(r.range(0, 1));
      v.flags = r.chance(0.05) ? 1u << r.below(7) : 0u;  // bit 6: a failed snap, not a clip bit
    }
    Draw draw;
    draw.topology = Topology::LineList;
    draw.state.line_width = r.chance(0.5) ? 1.0f : float(r.range(1, 40));
    for (uint32_t i = 0; i < lines; ++i) {  // lines at the bounds: a span of 32000 px, y across +-1e7
      if (!r.chance(0.05)) continue;
      FastVertex& a = vertices[2 * size_t(i)];
      FastVertex& b = vertices[2 * size_t(i) + 1];
      a.flags = b.flags = 0;
      if (r.chance(0.5)) {  // (x_hi - x_lo) + (y_hi - y_lo) + 4 * margin = 32000 exactly, or a step off
        const float margin4 = 4.0f * (std::max(draw.state.line_width, 1.0f) + 3.0f);
        a.x = 0.0f;
        a.y = b.y = 100.0f;
        b.x = 32000.0f - margin4 + float(int(r.below(3)) - 1) * 0.00390625f;
      } else {  // a short line across the bound of -1e7 or +1e7
        const float side = r.chance(0.5) ? 1.0f : -1.0f;
        a.x = b.x = 10.0f;
        a.y = side * 1e7f - 3.0f;
        b.y = side * 1e7f + 3.0f;
      }
    }
    draw.positions_clip.resize(vertices.size());  // only their count is read
    const float margin = reach_margin(draw, true);
    const uint32_t begin = r.below(lines), end = begin + r.below(lines - begin + 1);
    std::vector<uint32_t> reach(lines, 0xDEADBEEFu);
    line_list_reach_avx2(vertices.data(), begin, end, margin, tiles_y, reach.data());
    for (uint32_t i = 0; i < lines; ++i) {
      const uint32_t expected =
          i >= begin && i < end
              ? pack_tile_rows(listed_row_span(draw, vertices.data(), vertices.size(), 2, i, margin), tiles_y)
              : 0xDEADBEEFu;
      ASSERT_EQ(reach[i], expected) << "trial " << trial << " line " << i << " of [" << begin << ", " << end << "): ("
                                    << vertices[2 * i].x << ", " << vertices[2 * i].y << ") - ("
                                    << vertices[2 * i + 1].x << ", " << vertices[2 * i + 1].y << ")";
    }
  }
}

// The block-row phase's shortcut: whenever span_tile_rows_avx2 answers for a run of blocks, each
// block's answer is the one list_block_tile_rows_avx2 gives it alone; otherwise it writes
// nothing. Meshes with local indices (the shortcut's case), far and out-of-range indices, unknown
// rows and draw regions that cut the rows.
TEST(FastBlockRows, SpanAnswersAsBlockByBlock) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the block-row phase does not run";
  fast_test::Random r(11);
  int answered = 0, declined = 0, several_rows = 0, outside = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const uint32_t positions = 64 + r.below(6000);
    const uint32_t per_row = 16 + r.below(2000);  // positions per tile row of the mesh
    std::vector<int16_t> tile_rows(positions + 8, 0);
    for (uint32_t i = 0; i < positions; ++i)
      tile_rows[i] = r.chance(0.0005) ? unknown_row(1u << r.below(7)) : int16_t(int32_t(i / per_row) - 1);
    if (trial % 4 == 3) {  // every position to clip (a camera's mesh behind it), mostly outside one plane
      const uint32_t plane = 1u << r.below(6);
      for (uint32_t i = 0; i < positions; ++i) {
        const uint32_t flags = r.chance(0.002)   ? 1u << r.below(7)  // another plane, or a failed snap alone
                               : r.chance(0.001) ? 0u                // a known row among them
                                                 : plane | (r.chance(0.3) ? 1u << r.below(7) : 0u);
        tile_rows[i] = flags != 0 ? unknown_row(flags) : int16_t(r.below(16));
      }
    }
    const uint32_t n = 1 + r.below(kSpanBlocks);
    const uint32_t base = r.below(positions), spread = r.chance(0.2) ? positions : 1 + r.below(600);
    std::vector<uint32_t> indices(24 * n);
    for (uint32_t& index : indices) index = std::min(positions - 1, base + r.below(spread));
    if (r.chance(0.02)) indices[r.below(24 * n)] = positions + r.below(3);  // out of range
    const int32_t y0 = int32_t(r.below(300)), y1 = y0 + int32_t(r.below(400));
    const PixelRect region{0, y0, 1023, y1};
    std::vector<uint32_t> spans(n, 0x12345678u);
    if (!span_tile_rows_avx2(indices.data(), n, tile_rows.data(), positions, region, spans.data())) {
      ++declined;
      for (uint32_t b = 0; b < n; ++b)
        ASSERT_EQ(spans[b], 0x12345678u) << "trial " << trial << ": wrote when declining";
      continue;
    }
    ++answered;
    outside += is_unknown_row(tile_rows[indices[0]]) ? 1 : 0;
    std::vector<uint32_t> alone(n);
    for (uint32_t b = 0; b < n; ++b) {
      bool bad = false;
      alone[b] = list_block_tile_rows_avx2(indices.data() + 24 * b, tile_rows.data(), positions, region, bad);
      ASSERT_FALSE(bad) << "trial " << trial << ": answered for a bad index";
      ASSERT_EQ(spans[b], alone[b]) << "trial " << trial << " block " << b;
    }
    if (std::any_of(alone.begin(), alone.end(), [](uint32_t rows) { return (rows & 0xFFFFu) < (rows >> 16); }))
      ++several_rows;
  }
  EXPECT_GT(answered, 1000);
  EXPECT_GT(declined, 1000);
  EXPECT_GT(outside, 200);  // answered kNoRow for ranges outside one plane
  EXPECT_EQ(several_rows, 0);
}

// The walks' skip for a unit of one run of tiles: next_block_in_run_avx2 returns the first block
// whose rows hold the unit's tile row (or are kBlockAnyRow) and whose columns meet its run (or are
// kColumnsAny or kColumnsUnknown), eight at a time and in its last few blocks alone. Random rows
// and columns, every kind of value, runs of blocks that miss before the one that meets.
TEST(FastBlockRows, RunSkipFindsTheFirstBlockThatMayReachTheRun) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the walks of small blocks do not run";
  fast_test::Random r(23);
  const int32_t tiles = 16;
  const auto reference = [](uint32_t rows, uint32_t columns, int32_t row, int32_t first, int32_t last) {
    if (rows == kBlockAnyRow) return true;
    if (int32_t(rows & 0xFFFFu) > row || int32_t(rows >> 16) < row) return false;
    if (columns == kColumnsAny || columns == kColumnsUnknown) return true;
    const int32_t x0 = int32_t(columns & 0xFFFFu) - 1, x1 = int32_t(columns >> 16) - 1;
    return x0 <= last && x1 >= first;
  };
  int found = 0, none = 0, past_eight = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const uint32_t n = 1 + r.below(80);
    std::vector<uint32_t> rows(n), columns(n);
    const int32_t row = int32_t(r.below(tiles)), first = int32_t(r.below(tiles));
    const int32_t last = first + int32_t(r.below(uint32_t(tiles - first)));
    const double meets = r.chance(0.5) ? 0.02 : 0.3;  // mostly long runs of blocks that miss
    for (uint32_t b = 0; b < n; ++b) {
      const uint32_t lo = r.below(tiles), hi = r.chance(0.1) ? r.below(tiles) : lo + r.below(3);
      rows[b] = r.chance(meets * 0.1) ? kBlockAnyRow : r.chance(0.1) ? kNoRow : lo | hi << 16;
      const int32_t t0 = int32_t(r.below(tiles + 2)) - 1, t1 = r.chance(0.1) ? -1 : t0 + int32_t(r.below(4));
      const uint32_t packed = uint32_t(t0 + 1) | uint32_t(std::min(t1, tiles) + 1) << 16;
      columns[b] = r.chance(meets * 0.1) ? kColumnsAny : r.chance(meets * 0.1) ? kColumnsUnknown : packed;
    }
    const uint32_t begin = r.below(n), end = begin + r.below(n - begin + 1);
    uint32_t expected = begin;
    while (expected < end && !reference(rows[expected], columns[expected], row, first, last)) ++expected;
    const uint32_t got = next_block_in_run_avx2(rows.data(), columns.data(), begin, end, row, first, last);
    ASSERT_EQ(got, expected) << "trial " << trial << " row " << row << " run " << first << ".." << last;
    (expected < end ? found : none) += 1;
    past_eight += expected >= begin + 8 && expected < end ? 1 : 0;
  }
  EXPECT_GT(found, 5000);
  EXPECT_GT(none, 2000);
  EXPECT_GT(past_eight, 1000);
}

// A full block with a corner to clip: kNoRow exactly when every lane has its three corners outside
// one clip plane (the set-up would drop every lane), else kBlockAnyRow; without such a corner the
// block's rows. Blocks of corners mostly outside, some outside different planes, some inside.
TEST(FastBlockRows, BlocksWithEveryLaneOutsideOnePlaneAreLeftOut) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: the block-row phase does not run";
  fast_test::Random r(13);
  constexpr uint32_t kPositions = 512;
  int left_out = 0, kept = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::vector<FastVertex> vertices(kPositions);
    std::vector<int16_t> tile_rows(kPositions + 8, 0);
    const double inside = trial % 2 == 0 ? 0.0 : 0.3;
    for (uint32_t i = 0; i < kPositions; ++i) {
      const uint32_t plane = 1u << r.below(6);  // mostly the same plane: behind the camera, say
      uint32_t flags = r.chance(inside) ? 0 : r.chance(0.97) ? 1u : plane | (r.chance(0.3) ? 2u : 0u);
      if (trial % 4 == 3) flags = 0;
      // a failed snap is not a clip bit: in every fourth trial most corners failed to snap alone
      const uint32_t snap = r.chance(trial % 4 == 3 ? 0.97 : 0.05) ? kVertexSnapFailed : 0;
      vertices[i] = FastVertex{0, 0, 0, flags | snap};
      tile_rows[i] = (flags | snap) != 0 ? unknown_row(flags | snap) : int16_t(r.below(16));
    }
    std::vector<uint32_t> indices(24);
    for (uint32_t& index : indices) index = r.below(kPositions);
    uint32_t shared_all = ~0u;
    bool unknown = false;
    for (int l = 0; l < 8; ++l) {
      uint32_t shared = kVertexClipBits;
      for (int k = 0; k < 3; ++k) {
        shared &= vertices[indices[size_t(3 * l + k)]].flags;
        unknown = unknown || is_unknown_row(tile_rows[indices[size_t(3 * l + k)]]);
      }
      shared_all = std::min(shared_all, shared);  // 0 when some lane shares no plane
    }
    bool bad = false;
    const uint32_t rows =
        list_block_tile_rows_avx2(indices.data(), tile_rows.data(), kPositions, PixelRect{0, 0, 1023, 1023}, bad);
    ASSERT_FALSE(bad);
    if (!unknown) {
      ASSERT_NE(rows, kBlockAnyRow) << "trial " << trial;
      ASSERT_NE(rows, kNoRow) << "trial " << trial;
      continue;
    }
    ASSERT_EQ(rows, shared_all != 0 ? kNoRow : kBlockAnyRow) << "trial " << trial;
    ++(shared_all != 0 ? left_out : kept);
  }
  EXPECT_GT(left_out, 200);
  EXPECT_GT(kept, 200);
}

// The tile rows' assignment: every row to exactly one of the workers, the same
// answer every time, and on a skewed estimate (perspective's: one row 40% of the work) a split
// close to the best whole rows allow, where r % 2 gives 61/39.
std::vector<uint64_t> worker_loads(const std::vector<uint64_t>& weights, const std::vector<uint32_t>& owner,
                                   uint32_t workers) {
  std::vector<uint64_t> load(workers, 0);
  for (size_t r = 0; r < weights.size(); ++r) load[owner[r]] += weights[r];
  return load;
}

TEST(FastRowBalance, EveryRowOwnedOnceDeterministicAndBalanced) {
  const std::vector<uint64_t> skewed = {1, 1, 1, 1, 1, 1, 40, 880, 460, 170, 140, 120, 100, 100, 100, 100};
  const uint64_t total = std::accumulate(skewed.begin(), skewed.end(), uint64_t{0});
  fast_test::Random random(23);
  std::vector<uint64_t> noisy(37);
  for (uint64_t& w : noisy) w = random.below(1000) + (random.chance(0.1) ? 20000 : 0);
  for (const std::vector<uint64_t>& weights : {skewed, noisy, std::vector<uint64_t>(16, 5), std::vector<uint64_t>{}}) {
    const uint64_t sum = std::accumulate(weights.begin(), weights.end(), uint64_t{0});
    const uint64_t heaviest = weights.empty() ? 0 : *std::max_element(weights.begin(), weights.end());
    for (uint32_t workers = 1; workers <= 20; ++workers) {
      SCOPED_TRACE("rows " + std::to_string(weights.size()) + " workers " + std::to_string(workers));
      const std::vector<uint32_t> owner = balance_rows(weights, workers);
      ASSERT_EQ(owner.size(), weights.size());
      EXPECT_EQ(owner, balance_rows(weights, workers));
      for (const uint32_t w : owner) EXPECT_LT(w, workers);
      const std::vector<uint64_t> load = worker_loads(weights, owner, workers);
      // greedy list scheduling: no worker ends above the mean by more than one row's weight
      EXPECT_LE(*std::max_element(load.begin(), load.end()), sum / workers + heaviest);
      if (workers <= weights.size() && heaviest > 0) {  // every worker gets a row
        for (const uint64_t l : load) EXPECT_GT(l, 0u);
      }
    }
  }
  const std::vector<uint64_t> two = worker_loads(skewed, balance_rows(skewed, 2), 2);
  EXPECT_LE(std::max(two[0], two[1]) * 1000, total * 510);  // 50.5% here; r % 2 gives 61%
  const std::vector<uint64_t> four = worker_loads(skewed, balance_rows(skewed, 4), 4);
  EXPECT_EQ(*std::max_element(four.begin(), four.end()), 880u);  // the heavy row alone bounds it
  const std::vector<uint32_t> even = balance_rows(std::vector<uint64_t>(16, 5), 3);
  const std::vector<uint64_t> counts = worker_loads(std::vector<uint64_t>(16, 1), even, 3);
  EXPECT_EQ(*std::max_element(counts.begin(), counts.end()) - *std::min_element(counts.begin(), counts.end()), 1u);
  // the estimate: a row no block reaches costs its clear; a reached row its fill, more per block
  EXPECT_LT(tile_row_weight(0, 16), tile_row_weight(1, 16));
  EXPECT_LT(tile_row_weight(1, 16), tile_row_weight(2, 16));
  EXPECT_LT(tile_row_weight(3, 8), tile_row_weight(3, 16));
}

// Rows shared out by the workers' speeds (a worker whose core another process shares): equal
// speeds give the assignment without speeds; a worker at half speed gets about a third of two
// workers' rows, and no worker finishes (load / speed) later than the mean finish by more than one
// row's weight over its speed; contiguous runs follow the speeds' proportions, in order.
TEST(FastRowBalance, RowsSharedOutByTheWorkersSpeeds) {
  fast_test::Random random(31);
  std::vector<uint64_t> weights(64);
  for (uint64_t& w : weights) w = 100 + random.below(900);
  const uint64_t heaviest = *std::max_element(weights.begin(), weights.end());
  const uint64_t sum = std::accumulate(weights.begin(), weights.end(), uint64_t{0});
  for (const uint32_t workers : {1u, 2u, 3u, 8u}) {
    SCOPED_TRACE("workers " + std::to_string(workers));
    EXPECT_EQ(balance_rows(weights, workers, std::vector<double>(workers, 1.0)), balance_rows(weights, workers));
    EXPECT_EQ(contiguous_runs(16, workers, std::vector<double>(workers, 1.0)), contiguous_runs(16, workers));
    std::vector<double> speeds(workers, 1.0);
    speeds[workers - 1] = 0.5;
    const std::vector<uint32_t> owner = balance_rows(weights, workers, speeds);
    EXPECT_EQ(owner, balance_rows(weights, workers, speeds));
    const std::vector<uint64_t> load = worker_loads(weights, owner, workers);
    const double capacity = std::accumulate(speeds.begin(), speeds.end(), 0.0);
    for (uint32_t w = 0; w < workers; ++w)
      EXPECT_LE(double(load[w]) / speeds[w], double(sum) / capacity + double(heaviest) / speeds[w]) << w;
    const std::vector<uint32_t> runs = contiguous_runs(16, workers, speeds);
    ASSERT_EQ(runs.size(), 16u);
    EXPECT_TRUE(std::is_sorted(runs.begin(), runs.end()));
    for (const uint32_t w : runs) EXPECT_LT(w, workers);
  }
  const std::vector<uint64_t> two = worker_loads(weights, balance_rows(weights, 2, {1.0, 0.5}), 2);
  EXPECT_NEAR(double(two[1]) / double(sum), 1.0 / 3.0, 0.03);
  EXPECT_EQ(contiguous_runs(16, 2, {1.0, 0.5}),
            (std::vector<uint32_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1}));
  EXPECT_EQ(contiguous_runs(16, 2), (std::vector<uint32_t>{0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1}));
}

// balance_tiles: rows as balance_rows while no row weighs more than a quarter over a worker's
// share; otherwise the heavy rows cut into runs of whole tiles, every tile in exactly one unit,
// each unit one run of one row, units in order of their estimate, heaviest first.
TEST(FastRowBalance, HeavyRowsCutIntoRunsOfTiles) {
  const std::vector<uint64_t> even(16, 5);
  const TileUnits rows = balance_tiles(even, 16, 4);
  EXPECT_FALSE(rows.queued);
  EXPECT_FALSE(cuts_rows(even, 16, 4));
  // a row up to a quarter over a worker's share stays whole (kCutShareNum / kCutShareDen)
  std::vector<uint64_t> near(16, 100);
  near[3] = 120;  // share ceil(1,620 / 16) = 102: 1.18 shares
  EXPECT_FALSE(cuts_rows(near, 16, 16));
  EXPECT_FALSE(balance_tiles(near, 16, 16).queued);
  near[3] = 140;  // share 103: 1.36 shares
  EXPECT_TRUE(cuts_rows(near, 16, 16));
  EXPECT_TRUE(balance_tiles(near, 16, 16).queued);
  EXPECT_EQ(rows.count, 4u);
  const std::vector<uint32_t> by_row = balance_rows(even, 4);
  for (size_t t = 0; t < rows.unit.size(); ++t) EXPECT_EQ(rows.unit[t], by_row[t / 16]);
  const std::vector<uint64_t> skewed = {1, 1, 1, 1, 1, 1, 40, 880, 460, 170, 140, 120, 100, 100, 100, 100};
  for (const uint32_t workers : {2u, 4u, 16u}) {
    SCOPED_TRACE("workers " + std::to_string(workers));
    const TileUnits cut = balance_tiles(skewed, 16, workers);
    EXPECT_EQ(cut.queued, workers > 2);  // 880 of 2,221: more than a quarter, not more than half
    EXPECT_EQ(cuts_rows(skewed, 16, workers), cut.queued);
    EXPECT_FALSE(cuts_rows(skewed, 1, workers));  // one tile a row: nothing to cut
    ASSERT_EQ(cut.unit.size(), skewed.size() * 16);
    EXPECT_EQ(cut, balance_tiles(skewed, 16, workers));
    for (const uint32_t u : cut.unit) EXPECT_LT(u, cut.count);
    if (!cut.queued) continue;
    std::vector<uint64_t> weight(cut.count, 0);
    std::vector<int> row_of(cut.count, -1);
    for (size_t t = 0; t < cut.unit.size(); ++t) {
      const uint32_t u = cut.unit[t];
      ASSERT_LT(u, cut.count);
      const int row = int(t / 16);
      if (row_of[u] < 0) row_of[u] = row;
      EXPECT_EQ(row_of[u], row);                 // one row
      if (t % 16 > 0 && cut.unit[t - 1] != u) {  // a unit's tiles are one run
        for (size_t k = t + 1; k < size_t(row + 1) * 16; ++k) EXPECT_NE(cut.unit[k], cut.unit[t - 1]);
      }
      weight[u] += skewed[size_t(row)];
    }
    const uint64_t share = (std::accumulate(skewed.begin(), skewed.end(), uint64_t{0}) + workers - 1) / workers;
    uint32_t heavy_units = 0;
    for (uint32_t u = 0; u < cut.count; ++u) heavy_units += row_of[u] == 7 ? 1 : 0;
    EXPECT_EQ(heavy_units, std::min<uint64_t>(16, (kPiecesPerShare * 880 + share - 1) / share));
    for (uint32_t u = 1; u < cut.count; ++u) EXPECT_GE(weight[u - 1] / 16, weight[u] / 16);  // estimates
  }
}

}  // namespace
}  // namespace rastercmp::cpu::fast
