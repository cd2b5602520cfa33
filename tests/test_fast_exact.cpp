// The fast CPU path against the exact path: identical owner and depth bytes, at 1 and 2 threads,
// with every instruction set the host runs (the scalar twins, AVX2, AVX-512), on seeded random
// scenes, on every built-in scene and on small versions of the benchmark scenes
// (docs/performance.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench_scenes.hpp"
#include "cpu_raster/fast/worker_pool.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/scene_io.hpp"
#include "tests/test_differential_scenes.hpp"
#include "tests/test_fast_support.hpp"

namespace rastercmp {
namespace {

// The mesh families (the suite's longest tests) run half their seeds in the sanitizer build
// (make test's second pass): the Release pass runs them all, and every seed takes the sanitizers
// through the same code (docs/reliability.md, "Cost").
#ifdef RASTERCMP_SANITIZER_BUILD
constexpr uint64_t kMeshSeedDivisor = 2;
#else
constexpr uint64_t kMeshSeedDivisor = 1;
#endif

using fast_test::expect_fast_matches;
using fast_test::render_exact;
using fast_test::render_fast;
using fast_test::same_bytes;

class FastRandomScenes : public ::testing::TestWithParam<uint64_t> {};

TEST_P(FastRandomScenes, MatchExactPath) {
  const Scene scene = fast_test::random_scene(GetParam());
  expect_fast_matches(scene, /*fma=*/GetParam() % 5 != 0);
}

INSTANTIATE_TEST_SUITE_P(Seeds, FastRandomScenes, ::testing::Range<uint64_t>(1, 121),
                         [](const ::testing::TestParamInfo<uint64_t>& param_info) {
                           return "seed_" + std::to_string(param_info.param);
                         });

// Many small triangles in one big draw: the batching and tile-row split at real sizes.
TEST(FastDenseScenes, ManyTrianglesAcrossTileRows) {
  for (uint64_t seed = 200; seed < 206; ++seed) {
    fast_test::RandomSceneSpec spec;
    spec.allow_multisample = false;
    spec.allow_lines = false;
    spec.max_side = 300;
    spec.max_primitives = 400;
    expect_fast_matches(fast_test::random_scene(seed, spec), true);
  }
}

// Large draws cut into the driver's chunks, one chunk pipelined, slivers on both sides of each
// boundary (tests/test_differential_scenes.hpp): the float cull applies per chunk (§1.5, §2.6).
TEST(FastChunkedDraws, PipelinedChunksMatchExactPath) {
  for (uint32_t seed = 1; seed <= 6; ++seed) expect_fast_matches(differential::chunked_draws(seed), true);
}

class FastLayeredScenes : public ::testing::TestWithParam<uint64_t> {};

TEST_P(FastLayeredScenes, MatchExactPath) {
  expect_fast_matches(fast_test::layered_scene(GetParam()), GetParam() % 4 != 0, {1u, 2u, 3u});
}

INSTANTIATE_TEST_SUITE_P(Seeds, FastLayeredScenes, ::testing::Range<uint64_t>(1, 41),
                         [](const ::testing::TestParamInfo<uint64_t>& param_info) {
                           return "seed_" + std::to_string(param_info.param);
                         });

class FastMidTriangles : public ::testing::TestWithParam<uint64_t> {};

TEST_P(FastMidTriangles, MatchExactPath) {
  expect_fast_matches(fast_test::mid_triangle_scene(GetParam()), GetParam() % 3 != 0);
}

INSTANTIATE_TEST_SUITE_P(Seeds, FastMidTriangles, ::testing::Range<uint64_t>(1, 41),
                         [](const ::testing::TestParamInfo<uint64_t>& param_info) {
                           return "seed_" + std::to_string(param_info.param);
                         });

class FastSmallMeshes : public ::testing::TestWithParam<uint64_t> {};

TEST_P(FastSmallMeshes, MatchExactPath) {
  expect_fast_matches(fast_test::small_mesh_scene(GetParam()), GetParam() % 4 != 0, {1u, 2u, 3u});
}

INSTANTIATE_TEST_SUITE_P(Seeds, FastSmallMeshes, ::testing::Range<uint64_t>(1, 1 + 40 / kMeshSeedDivisor),
                         [](const ::testing::TestParamInfo<uint64_t>& param_info) {
                           return "seed_" + std::to_string(param_info.param);
                         });

// A grid of columns x rows cells over clip x in [-1, 1] and y in [y0, y0 + height], each vertex
// moved by up to 0.3 of a cell and given a random depth, as an indexed list of two triangles a cell.
Draw jittered_grid(fast_test::Random& r, uint32_t columns, uint32_t rows, float y0, float height) {
  Draw draw;
  for (uint32_t j = 0; j <= rows; ++j)
    for (uint32_t i = 0; i <= columns; ++i)
      draw.positions_clip.emplace_back(-1.0f + 2.0f * (float(i) + float(r.range(-0.3, 0.3))) / float(columns),
                                       y0 + height * (float(j) + float(r.range(-0.3, 0.3))) / float(rows),
                                       float(r.range(0.0, 1.0)), 1.0f);
  for (uint32_t j = 0; j < rows; ++j)
    for (uint32_t i = 0; i < columns; ++i) {
      const uint32_t v = j * (columns + 1) + i;
      for (uint32_t k : {v, v + 1, v + columns + 2, v, v + columns + 2, v + columns + 1}) draw.indices.push_back(k);
    }
  return draw;
}

// A jittered mesh of cells of cell_min..cell_max pixels, a list, strip or fan over the same
// indices (read as strips and fans they make triangles that overlap inside a block, so the lanes'
// order decides pixels), drawn twice; the format and first op follow the seed.
Scene jittered_mesh(uint64_t seed, double cell_min, double cell_max) {
  fast_test::Random r(seed);
  Scene scene;
  scene.name = "test.fast.mesh." + std::to_string(seed);
  scene.width = 40 + r.below(60);
  scene.height = 70 + r.below(70);  // two or more tile rows
  scene.depth_format = DepthFormat(seed % 4);
  const uint32_t columns = uint32_t(float(scene.width) / float(r.range(cell_min, cell_max)));
  const uint32_t rows = uint32_t(float(scene.height) / float(r.range(cell_min, cell_max)));
  Draw draw = jittered_grid(r, columns, rows, -1.0f, 2.0f);
  draw.topology = seed % 3 == 0   ? Topology::TriangleList
                  : seed % 3 == 1 ? Topology::TriangleStrip
                                  : Topology::TriangleFan;
  if (seed % 6 == 0) draw.topology = Topology::TriangleList;
  // A fan shares its first corner: over the whole mesh its triangles would span the frame and
  // the test would time the exact path's big triangles. Two rows of cells keep the lanes that
  // overlap around the shared corner.
  if (draw.topology == Topology::TriangleFan) draw.indices.resize(std::min<size_t>(draw.indices.size(), 12 * columns));
  draw.state.depth.compare_op = CompareOp((seed / 4) % 8);
  draw.state.depth.write_enable = seed % 5 != 0;
  scene.draws.push_back(draw);
  draw.state.depth.compare_op = CompareOp((seed / 4 + 1) % 8);  // a second pass over the same mesh
  scene.draws.push_back(std::move(draw));
  return scene;
}

// Cells of about a pixel: most blocks' grid lanes fit in 4x4 pixels and take the packed layout
// (small_triangles.hpp, grid_words).
TEST(FastTinyMeshes, PackedGridLayoutMatchesExactPath) {
  for (uint64_t seed = 1; seed <= 12 / kMeshSeedDivisor; ++seed)
    expect_fast_matches(jittered_mesh(seed, 0.7, 1.6), seed % 2 == 0, {1u, 2u});
}

// Cells of 2-4 pixels: blocks in the 8x8 layout, which an AVX-512 host draws with the window
// compositor (small_window.hpp), also across tile rows (workers' rows cut the window); every
// format and compare op.
TEST(FastWindowMeshes, WindowCompositorMatchesExactPath) {
  for (uint64_t seed = 1; seed <= 32 / kMeshSeedDivisor; ++seed)
    expect_fast_matches(jittered_mesh(seed, 2.0, 4.0), seed % 2 == 0, {1u, 2u, 3u});
}

// The workers share the tile rows out by estimated work (row_balance.hpp), not as
// r % workers. A 200x320 frame (five tile rows): a quad over the left part of every row (the
// right tiles of rows 0, 1, 3 and 4 are cleared untouched), then a jittered mesh of 2-4 pixel cells
// crowded into tile row 2 (nearly every block's work there), then big and thin triangles across
// rows 1-3 and 0-4 with another compare op. At 2, 3 and 4 workers the crowded row gets a worker of
// its own and the others share the rest in an order r % workers would not give (2 workers: rows
// 0, 1, 3, 4 on one). A worker that picks its blocks by the interleaved rule (owns_tile_rows)
// leaves blocks of its rows out: wrong bytes at 3 and 4 workers.
Scene crowded_row_scene(uint64_t seed) {
  fast_test::Random r(seed);
  Scene scene;
  scene.name = "test.fast.crowded_row." + std::to_string(seed);
  scene.width = 200;
  scene.height = 320;  // tile row 2 (pixels 128-191) is centred: the mesh is in it either way up
  scene.depth_format = DepthFormat(seed % 4);
  Draw quad;
  for (const auto& [x, y] : {std::pair{-1.0f, -1.0f}, {0.2f, -1.0f}, {-1.0f, 1.0f}, {0.2f, 1.0f}})
    quad.positions_clip.emplace_back(x, y, 0.8f + 0.05f * x + 0.05f * y, 1.0f);
  quad.indices = {0, 1, 3, 0, 3, 2};
  scene.draws.push_back(quad);
  const uint32_t columns = 200 / 3, rows = 48 / 3;  // pixels 136-184: ndc y in [-0.15, 0.15]
  Draw mesh = jittered_grid(r, columns, rows, -0.15f, 0.3f);
  mesh.state.depth.compare_op = CompareOp((seed / 4) % 8);
  mesh.state.depth.write_enable = seed % 3 != 0;
  scene.draws.push_back(std::move(mesh));
  Draw across;  // rows 1-3 (a thin sliver and a wide triangle) and 0-4
  across.positions_clip = {
      {-0.9f, -0.55f, 0.3f, 1.0f}, {-0.85f, 0.55f, 0.5f, 1.0f}, {-0.8f, -0.5f, 0.4f, 1.0f},  // thin, rows 1-3
      {-0.2f, -0.5f, 0.6f, 1.0f},  {0.9f, 0.1f, 0.2f, 1.0f},    {0.1f, 0.55f, 0.7f, 1.0f},   // wide, rows 1-3
      {0.3f, -0.98f, 0.1f, 1.0f},  {0.95f, 0.98f, 0.9f, 1.0f},  {0.5f, 0.9f, 0.5f, 1.0f}};   // rows 0-4
  across.state.depth.compare_op = CompareOp((seed / 4 + 3) % 8);
  scene.draws.push_back(std::move(across));
  return scene;
}

TEST(FastRowBalance, WorkCrowdedIntoOneTileRowMatchesExactPath) {
  for (uint64_t seed = 1; seed <= 8; ++seed)
    expect_fast_matches(crowded_row_scene(seed), seed % 2 == 0, {1u, 2u, 3u, 4u});
}

// Rows shared out by a skewed pace (a worker whose core is shared: WorkerPool::record_pace, then
// balance_rows and contiguous_runs by the speeds) give the same bytes: the crowded row, a mesh,
// perspective and lines at 2 and 3 workers, each pool's last worker measured at a quarter of the
// others' rate (the renders' own band phases may move the pace further: any assignment gives
// the same bytes), then the pace forgotten.
TEST(FastRowBalance, RowsSharedOutByASkewedPaceMatchExactPath) {
  for (const uint32_t workers : {2u, 3u}) {
    cpu::fast::WorkerPool& pool = cpu::fast::worker_pool(workers);
    pool.reset_pace();
    std::vector<double> work(workers, 100.0), seconds(workers, 0.004);
    seconds.back() = 0.016;
    pool.record_pace(work, seconds);
    const std::vector<double> speeds = pool.relative_speeds();
    EXPECT_EQ(speeds.front(), 1.0) << workers;
    EXPECT_NEAR(speeds.back(), 0.25, 1e-12) << workers;
  }
  for (uint64_t seed = 1; seed <= 4; ++seed) expect_fast_matches(crowded_row_scene(seed), seed % 2 == 0, {2u, 3u});
  expect_fast_matches(bench::grid_scene(120, 256), true, {2u, 3u});
  expect_fast_matches(bench::perspective_scene(120, 256), false, {2u, 3u});
  expect_fast_matches(bench::lines_scene(2000, 256), true, {2u, 3u});
  expect_fast_matches(bench::msaa_grid_scene(24, 160), true, {2u, 3u});
  for (const uint32_t workers : {2u, 3u}) {
    cpu::fast::worker_pool(workers).reset_pace();
    EXPECT_EQ(cpu::fast::worker_pool(workers).relative_speeds(), std::vector<double>(workers, 1.0)) << workers;
  }
}

// A row over a worker's share is cut into runs of its tiles, which the workers take from a queue
// (balance_tiles): small lanes across a run's border take the scalar set-up, blocks are set up by
// the runs their lanes reach, clipped pieces, big triangles, lines (exact rows cut to the run's
// columns) and the clears go tile by tile. The crowded row of crowded_row_scene at 3-8 workers
// (with a draw of lines after the mesh), perspective's horizon row at 4 and 16 workers; the band
// phase is then a queue of units (its tasks in the profile).
TEST(FastSharedRows, HeavyRowCutIntoRunsOfTilesMatchesExactPath) {
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    Scene scene = crowded_row_scene(seed);
    if (seed <= 4) {
      Draw lines = bench::lines_scene(400, 200, seed).draws[0];
      lines.state.depth.compare_op = CompareOp::LessOrEqual;
      scene.draws.push_back(std::move(lines));
    }
    expect_fast_matches(scene, seed % 2 == 0, {3u, 5u, 8u});
  }
  expect_fast_matches(bench::perspective_scene(120, 256), true, {4u, 16u});
  expect_fast_matches(bench::perspective_scene(200, 512), false, {16u});
  // Each pixel keeps the last triangle drawn over it: a lane a unit draws into another unit's
  // tile (or twice) shows, which under LESS it mostly would not.
  Scene last_wins = bench::perspective_scene(200, 512);
  last_wins.draws[0].state.depth.compare_op = CompareOp::Always;
  expect_fast_matches(last_wins, true, {16u});
  CpuOptions options;
  options.threads = 4;
  options.fma = false;
  cpu::fast::FastConfig config;
  cpu::fast::RenderProfile profile;
  config.profile = &profile;
  config.profile_threads = 1;  // four workers' jobs, one after another on one thread: the same bytes
  const Scene crowded = crowded_row_scene(3);
  EXPECT_TRUE(same_bytes(render_exact(crowded, false), cpu::fast::render_fast(crowded, options, config)));
  ASSERT_EQ(profile.phases.back().phase, "bands");
  EXPECT_GT(profile.phases.back().tasks.size(), 4u);
}

// The set-ups of a trailing pipelined run that meet a denormal (the reduced random scenes of
// tests/data/scenes/denormal-planes) after 40 draws of one small triangle each, which share the
// vertex phase's first task with them: each draw's clip bits, which decide its trailing run and
// its check, are its own.
TEST(FastVertexPhase, DrawsSharingATaskKeepTheirOwnClipBits) {
  const std::string root = std::string(RASTERCMP_SOURCE_DIR) + "/tests/data/scenes/denormal-planes";
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(root)) {
    const Scene original = load_scene_file(entry.path().string());
    Scene scene = original;
    scene.draws.clear();
    for (int k = 0; k < 40; ++k) {
      Draw small;
      small.name = "small " + std::to_string(k);
      const float x = -0.9f + 0.04f * float(k);
      small.positions_clip = {{x, -0.9f, 0.5f, 1.0f}, {x + 0.03f, -0.9f, 0.5f, 1.0f}, {x, -0.87f, 0.5f, 1.0f}};
      scene.draws.push_back(small);
    }
    scene.draws.insert(scene.draws.end(), original.draws.begin(), original.draws.end());
    for (const bool fma : {true, false}) expect_fast_matches(scene, fma);
    ++scenes;
  }
  EXPECT_EQ(scenes, 12);
}

// render_fast_side_by_side (the bench's suite row): scenes rendered side by side on the workers,
// each on one (a scene worker_count gives several first, with all of them), give each scene the
// exact path's bytes, into reused results too; the queue holds the one-worker scenes, largest
// estimate first.
TEST(FastSideBySide, ScenesSideBySideMatchExactPath) {
  std::vector<Scene> scenes;
  for (Scene& scene : bench::load_scene_suite(std::string(RASTERCMP_SOURCE_DIR) + "/scenes")) {
    try {
      render_exact(scene, true);
    } catch (const NotSupportedError&) {
      continue;
    }
    scenes.push_back(std::move(scene));
    if (scenes.size() == 40) break;
  }
  scenes.push_back(bench::grid_scene(60, 256));  // several workers
  CpuOptions options;
  options.fma = true;
  options.threads = 3;
  const std::vector<size_t> queue = cpu::fast::side_by_side_queue(scenes, options, cpu::fast::FastConfig{});
  EXPECT_EQ(queue.size(), scenes.size() - 1);
  const auto estimate = [&](size_t i) {
    uint64_t vertices = 0;
    for (const Draw& draw : scenes[i].draws) vertices += draw.vertex_count();
    return uint64_t(scenes[i].width) * scenes[i].height * scenes[i].samples + 16 * vertices;
  };
  for (size_t k = 1; k < queue.size(); ++k) EXPECT_GE(estimate(queue[k - 1]), estimate(queue[k]));
  std::vector<RenderResult> results;
  for (int round = 0; round < 2; ++round) {  // new results, then the same reused
    cpu::fast::render_fast_side_by_side(scenes, options, cpu::fast::FastConfig{}, results);
    ASSERT_EQ(results.size(), scenes.size());
    for (size_t i = 0; i < scenes.size(); ++i)
      EXPECT_TRUE(same_bytes(render_exact(scenes[i], true), results[i])) << scenes[i].name << " round " << round;
  }
}

// Triangles whose leftmost and topmost corners lie on a pixel's sample or 1/256 px beside it, with a
// vertical left edge, a horizontal top edge or neither, overlapping in depth: the fast path's
// rectangle (x0 = (min + 255) >> 8, band_worker.cpp) leaves out only a column or row with no
// sample in the triangle. A rectangle one column too narrow drops the covered samples of the
// left and top edges that lie on sample positions.
TEST(FastBoundingBox, CornersOnAndBesideSamplePositions) {
  Scene scene;
  scene.name = "fast.bbox.corners";
  scene.width = scene.height = 256;
  Draw draw;
  draw.name = "corners";
  const auto clip = [](double sample) { return float((sample + 0.5) / 128.0 - 1.0); };  // exact
  int cell = 0;
  for (int fx = -1; fx <= 1; ++fx) {
    for (int fy = -1; fy <= 1; ++fy, ++cell) {
      const double x = 10.0 + 80.0 * (cell % 3) + fx / 256.0, y = 10.0 + 80.0 * (cell / 3) + fy / 256.0;
      const double shapes[3][3][2] = {{{x, y}, {x, y + 50}, {x + 50, y + 20}},       // vertical left edge
                                      {{x, y}, {x + 50, y}, {x + 20, y + 50}},       // horizontal top edge
                                      {{x, y + 7}, {x + 45, y}, {x + 30, y + 55}}};  // neither
      for (int s = 0; s < 3; ++s) {
        for (const auto& corner : shapes[s])
          draw.positions_clip.emplace_back(clip(corner[0]), clip(corner[1]),
                                           0.7f - 0.2f * float(s) + 0.001f * float(corner[0] - x), 1.0f);
      }
    }
  }
  scene.draws.push_back(std::move(draw));
  expect_fast_matches(scene, true);
  expect_fast_matches(scene, false);
}

// The fast clear skips a tile's clear only when the first triangle replaces every value of it.
TEST(FastClear, TilesKeepTheirClearValuesUnderDepthWritesOff) {
  for (const DepthFormat format : {DepthFormat::D16Unorm, DepthFormat::X8D24Unorm, DepthFormat::D32Sfloat}) {
    Scene scene;
    scene.name = "test.fast.clear";
    scene.width = 150;
    scene.height = 130;
    scene.depth_format = format;
    scene.depth_clear = 0.75f;
    for (const bool write : {false, true}) {
      Draw draw;  // a quad over the whole framebuffer, in front of the clear value
      for (const glm::vec4& v : {glm::vec4(-1, -1, 0.25f, 1), glm::vec4(1, -1, 0.25f, 1), glm::vec4(1, 1, 0.25f, 1),
                                 glm::vec4(-1, -1, 0.25f, 1), glm::vec4(1, 1, 0.25f, 1), glm::vec4(-1, 1, 0.25f, 1)})
        draw.positions_clip.push_back(v);
      draw.state.depth.write_enable = write;
      scene.draws.push_back(draw);
    }
    expect_fast_matches(scene, true);
    scene.draws.pop_back();  // writes off alone: the depth buffer must still hold the clear value
    const RenderResult fast = render_fast(scene, true, 2, fast_test::best_isa());
    EXPECT_TRUE(same_bytes(render_exact(scene, true), fast));
  }
}

// Results rendered into reused buffers equal fresh ones (the fast clear leaves nothing behind).
TEST(FastClear, ReusedBuffersGiveTheSameBytes) {
  CpuOptions options;
  options.threads = 2;
  RenderResult reused;
  for (uint64_t seed = 1; seed < 12; ++seed) {
    const Scene scene = fast_test::layered_scene(seed);
    options.fma = lavapipe_fuses_on_this_host();
    render_cpu_fast_into(scene, options, reused);
    EXPECT_TRUE(same_bytes(render_exact(scene, options.fma), reused)) << "seed " << seed;
  }
}

TEST(FastBenchScenes, SmallVersionsMatchExactPath) {
  expect_fast_matches(bench::fill_layers_scene(true, 200, 6), true);
  expect_fast_matches(bench::fill_layers_scene(false, 200, 6), true);
  expect_fast_matches(bench::fill_layers_scene(false, 200, 6), false);
  expect_fast_matches(bench::grid_scene(60, 256), true);
  expect_fast_matches(bench::grid_scene(181, 256), true);  // about 1 px triangles
  expect_fast_matches(bench::perspective_scene(40, 192), true);
  expect_fast_matches(bench::perspective_scene(120, 256), true);  // triangles of 8-16 px, clipped ones
  expect_fast_matches(bench::lines_scene(300, 160), true);
  expect_fast_matches(bench::msaa_grid_scene(24, 96), true);
  expect_fast_matches(bench::engine_scene(480, 270), true);  // a real model: 115 draws, 121,496 triangles
}

// Lines and 4x frames (drawn by the exact rasterizer on each worker's tile rows): thousands of
// primitives piled onto a small frame, with a compare op under which the later of two primitives
// wins every tie (LESS_OR_EQUAL) or every sample (ALWAYS), so a primitive drawn out of order on
// some worker changes the bytes. Wide and Bresenham lines, a 4x grid drawn twice, and a scissor and
// fractional viewport offset that cut primitives at tile borders.
TEST(FastExactRows, ManyPrimitivesKeepTheirOrderOnEveryWorker) {
  for (const CompareOp op : {CompareOp::LessOrEqual, CompareOp::Always}) {
    Scene lines = bench::lines_scene(6221, 150);
    lines.draws[0].state.depth.compare_op = op;
    expect_fast_matches(lines, true, {1u, 3u});
    lines.draws[0].state.line_width = 3.0f;
    lines.draws[0].state.line_mode = LineMode::Bresenham;
    lines.scissor = Rect2D{5, 63, 140, 70};
    expect_fast_matches(lines, false, {2u});

    Scene msaa = bench::msaa_grid_scene(48, 140);  // 4,608 triangles a draw
    msaa.draws.push_back(msaa.draws[0]);
    for (Draw& draw : msaa.draws) draw.state.depth.compare_op = op;
    msaa.viewport = Viewport{-3.5f, 60.25f, 150.0f, 90.0f, 0.0f, 1.0f};
    expect_fast_matches(msaa, true, {1u, 2u, 3u});
  }
}

// Triangles that need clipping, set up once by the block-row phase and drawn from its table by
// every worker (clipped_pieces.hpp): two draws of a camera mesh crossing the view volume's sides
// and far plane (a table per draw, each worker's walk through it in order), at 2-4 workers.
TEST(FastClippedPieces, TableOfPiecesMatchesExactPath) {
  Scene scene = bench::perspective_scene(48, 160);
  Draw second = scene.draws.front();
  for (glm::vec4& p : second.positions_clip) p.y += 0.15f * p.w;  // shifted up the screen, overlapping
  second.state.depth.compare_op = CompareOp::LessOrEqual;
  scene.draws.push_back(std::move(second));
  expect_fast_matches(scene, true, {2u, 3u, 4u});
}

// Rows nothing draws into go to no worker and are cleared by whichever finishes first
// (FastFrame::unowned_rows): only where every block's rows are known. The huge triangle of
// scenes/triangle/huge/wraps_covers_all, its viewport moved to rows 32-95 of a 64x128 frame, is
// clipped into a piece that takes llvmpipe's wrapping set-up and covers rows 32-95: every worker
// draws it into its own rows wherever it meets it (its block keeps kBlockAnyRow). A second draw's
// small triangle (rows 73-86) is the only block with known rows: tile row 0, which no known block
// reaches, must still belong to a worker (left unowned, it would miss the piece). Without the
// huge triangle, row 0 is unowned and cleared.
TEST(FastUnownedRows, OnlyWhereEveryBlocksRowsAreKnown) {
  Scene scene;
  scene.name = "test.fast.unowned_rows";
  scene.width = 64;
  scene.height = 128;
  scene.viewport = Viewport{0, 32, 64, 64, 0, 1};
  Draw huge;
  huge.positions_clip = {
      {1.1e12f, 1.4e12f, 0.5f, 1.0f}, {-4e13f, 2.29e13f, 0.5f, 1.0f}, {9.2e16f, -3.18e17f, 0.5f, 1.0f}};
  scene.draws.push_back(huge);
  Draw small;
  small.positions_clip = {{-0.5f, 0.3f, 0.2f, 1.0f}, {0.5f, 0.3f, 0.2f, 1.0f}, {0.0f, 0.7f, 0.2f, 1.0f}};
  scene.draws.push_back(small);
  expect_fast_matches(scene, true, {2u, 3u});
  scene.draws.erase(scene.draws.begin());
  expect_fast_matches(scene, true, {2u, 3u});
}

// The depth bounds' audit (band_worker.hpp): a camera terrain drawn back to front, on which the
// bounds seldom help, has each worker turn them off part way through its draw (before the near
// rows, drawn last, reach their tiles); the next draw, one near-full-screen layer at z = 0.9,
// starts with them on again and must find those tiles with their bounds unknown, not the clear
// value's: against those the layer would pass every test and cover the nearer terrain (found by
// leaving update_bounds to draws with bounds on). At 1-3 workers.
TEST(FastBoundsAudit, BoundsTurnedOffPartWayKeepTheBytes) {
  Scene scene = bench::perspective_scene(200, 512);
  Draw layer = bench::fill_layers_scene(true, 512, 4).draws.front();  // back to front: the farthest first
  layer.positions_clip.resize(4);
  layer.indices.resize(6);
  scene.draws.push_back(std::move(layer));
  expect_fast_matches(scene, true, {1u, 2u, 3u});
}

// render_cpu_fast as the bench and render_cpu call it (its own choice of workers) on a scene big
// enough for two.
TEST(FastBenchScenes, ProductionEntryPointMatchesExactPath) {
  const Scene scene = bench::grid_scene(200, 512);
  CpuOptions options;
  options.fma = lavapipe_fuses_on_this_host();
  options.threads = 2;
  EXPECT_TRUE(same_bytes(render_exact(scene, options.fma), render_cpu_fast(scene, options)));
  EXPECT_TRUE(same_bytes(render_exact(scene, options.fma), render_cpu(scene, options)));
}

TEST(FastBuiltinScenes, EverySupportedSceneMatchesExactPath) {
  const std::string root = std::string(RASTERCMP_SOURCE_DIR) + "/scenes";
  const std::vector<Scene> scenes = bench::load_scene_suite(root);
  ASSERT_FALSE(scenes.empty());
  size_t compared = 0;
  for (const Scene& scene : scenes) {
    try {
      render_exact(scene, true);
    } catch (const NotSupportedError&) {
      continue;  // the exact path reports it; the fast path must do the same
    }
    expect_fast_matches(scene, true);
    ++compared;
  }
  EXPECT_GT(compared, scenes.size() / 2);
}

// What `describe` says of the Error a render throws ("" when it throws none).
template <class Error, class Render, class Describe>
std::string thrown(Render render, Describe describe) {
  try {
    render();
  } catch (const Error& e) {
    return describe(e);
  }
  return "";
}

// The JSON path of the InputError a render throws ("" when it throws none).
template <class Render>
std::string input_error_path(Render render) {
  return thrown<InputError>(render, [](const InputError& e) { return e.json_path(); });
}

// With several workers the fast path checks the index range where its block-row phase reads the
// indices (render_fast.cpp): the error is the exact path's, naming the first index out of range,
// wherever it lies (a whole block, the last block, a list's tail that makes no triangle, a strip,
// a fan), also when a later draw is not supported.
TEST(FastIndexCheck, SameErrorAsTheExactPath) {
  struct Case {
    Topology topology;
    size_t bad;       // the index made out of range (from the end when tail)
    bool tail;        // two indices appended past the last whole triangle, the second one bad
    bool point_draw;  // a second draw of points, not supported (reported only after the indices)
  };
  const Case cases[] = {
      {Topology::TriangleList, 100, false, false}, {Topology::TriangleList, 3 * 3200 - 2, false, false},
      {Topology::TriangleList, 0, true, false},    {Topology::TriangleStrip, 4000, false, false},
      {Topology::TriangleFan, 7, false, false},    {Topology::TriangleList, 2000, false, true}};
  for (const Case& c : cases) {
    Scene scene = bench::grid_scene(40, 256);  // 3200 triangles
    scene.source_path = "mesh.json";
    Draw& draw = scene.draws[0];
    draw.topology = c.topology;
    const uint32_t positions = uint32_t(draw.positions_clip.size());
    if (c.tail) {
      draw.indices.push_back(0);
      draw.indices.push_back(positions);
    } else {
      draw.indices[c.bad] = positions + 5;
      if (c.bad + 30 < draw.indices.size()) draw.indices[c.bad + 30] = positions;  // a later one too
    }
    if (c.point_draw) {
      Draw points;
      points.topology = Topology::PointList;
      points.positions_clip = {{0, 0, 0.5f, 1}};
      scene.draws.push_back(points);
    }
    const std::string expected = input_error_path([&] { render_exact(scene, true); });
    ASSERT_EQ(expected, "$.draws[0].indices[" + std::to_string(c.tail ? draw.indices.size() - 1 : c.bad) + "]");
    for (const uint32_t threads : {1u, 2u}) {
      for (const fast_test::FastIsa isa : fast_test::host_isas()) {
        SCOPED_TRACE(std::string(fast_test::isa_name(isa)) + " threads=" + std::to_string(threads) + " bad " +
                     std::to_string(c.bad));
        EXPECT_EQ(input_error_path([&] { render_fast(scene, true, threads, isa); }), expected);
      }
    }
  }
}

// The NotSupportedError message a render throws ("" when it throws none).
template <class Render>
std::string not_supported_message(Render render) {
  return thrown<NotSupportedError>(render, [](const NotSupportedError& e) { return std::string(e.what()); });
}

// Exact draws (a 4x frame) whose set-ups throw: a trailing pipelined run longer than one batch,
// each set-up meeting a denormal that changes it (rules §7.11), laid out bottom to top over four
// tile rows so that on several workers each meets a different first failure of its own rows (the
// workers leave out the primitives outside them). The render throws the exact path's error, the
// first failing primitive in submission order, at every worker count.
TEST(FastFailures, FirstFailingPrimitiveOfTheExactPathOnEveryWorkerCount) {
  Scene scene = fast_test::denormal_setup_batch_scene(60, false);
  scene.height = 256;
  scene.samples = 4;
  for (size_t k = 0; k < scene.draws[0].positions_clip.size(); ++k) {
    glm::vec4& v = scene.draws[0].positions_clip[k];
    if (k < 3) {
      v.z = 0.0f;  // the clipped first triangle sets up alike in both modes
      continue;
    }
    v.y = 0.9f - (v.y + 0.75f) * 2.6f;  // window rows 13-243, the first primitives at the bottom
  }
  const std::string expected = not_supported_message([&] { render_exact(scene, true); });
  ASSERT_NE(expected.find("draw 0 primitive 1:"), std::string::npos) << expected;
  for (const uint32_t threads : {1u, 2u, 3u, 4u}) {
    SCOPED_TRACE("threads=" + std::to_string(threads));
    EXPECT_EQ(not_supported_message([&] { render_fast(scene, true, threads, fast_test::best_isa()); }), expected);
  }
}

// A line draw whose every line leaves the clip volume (one pipelined chunk, the draw's trailing
// run, rules §7.11), its depths near the smallest normal float: each set-up meets a denormal that
// changes its depth plane. Three lines fit one batch: set up with denormals kept, the fast path's
// bytes are the exact path's, and the flushed set-up alone would differ from them. A hundred
// span batches: the render throws the exact path's error at every worker count.
Scene tiny_depth_lines_scene(uint32_t lines) {
  Scene scene;
  scene.name = "tiny depth lines";
  scene.width = scene.height = 64;
  scene.depth_format = DepthFormat::D32Sfloat;
  Draw draw;
  draw.topology = Topology::LineList;
  draw.state.depth.compare_op = CompareOp::Always;
  for (uint32_t k = 0; k < lines; ++k) {
    const float x = -0.9f + 0.017f * float(k % 100), y = -0.85f + 0.0163f * float(k % 97);
    const float z = 1.18e-38f * (1.0f + 0.02f * float(k % 90));
    draw.positions_clip.emplace_back(x, y, z, 1.0f);
    draw.positions_clip.emplace_back(x + 1.95f, y + 0.1f, z * (1.0f + 1e-5f * float(1 + k % 7)), 1.0f);
  }
  scene.draws.push_back(std::move(draw));
  return scene;
}

TEST(FastLines, TrailingRunSetUpsThatMeetDenormals) {
  const Scene kept = tiny_depth_lines_scene(3);
  const RenderResult exact = render_exact(kept, true);
  for (const uint32_t threads : {1u, 2u})
    EXPECT_TRUE(same_bytes(exact, render_fast(kept, true, threads, fast_test::best_isa()))) << threads;
  Scene flushed = kept;  // in a chunk without clipping the lines are set up in the flushed mode
  for (glm::vec4& v : flushed.draws[0].positions_clip) v.x = std::min(v.x, 0.99f);
  EXPECT_FALSE(same_bytes(exact, render_exact(flushed, true)));
  const Scene spanning = tiny_depth_lines_scene(100);
  const std::string expected = not_supported_message([&] { render_exact(spanning, true); });
  ASSERT_NE(expected.find("draw 0 primitive 0:"), std::string::npos) << expected;
  for (const uint32_t threads : {1u, 2u, 3u}) {
    SCOPED_TRACE("threads=" + std::to_string(threads));
    EXPECT_EQ(not_supported_message([&] { render_fast(spanning, true, threads, fast_test::best_isa()); }), expected);
  }
}

TEST(FastBuiltinScenes, NotSupportedStaysNotSupported) {
  const Scene scene = load_scene_file(std::string(RASTERCMP_SOURCE_DIR) + "/scenes/not_supported/point_list.json");
  EXPECT_THROW(render_fast(scene, true, 2, fast_test::best_isa()), NotSupportedError);
}

}  // namespace
}  // namespace rastercmp
