// Lines on the fast path's walk of exact draws (band_worker_exact.cpp) against the exact path:
// lines cut by the view volume's sides beside the workers' tile borders, with and without the
// reach phase's clipping (exact_reach.hpp), and frames drawn at a wider row pitch
// (frame_row_pitch, the thin rows' pairs). Same bytes, every kernel set the host runs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench_scenes.hpp"
#include "cpu_raster/fast/render_fast.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "tests/test_fast_support.hpp"

namespace rastercmp {
namespace {

using fast_test::expect_fast_matches;
using fast_test::render_exact;
using fast_test::same_bytes;

// A frame of width x height with one line list, empty, of lines `line_width` wide.
Scene line_list_scene(const std::string& name, uint32_t width, uint32_t height, float line_width) {
  Scene scene;
  scene.name = name;
  scene.width = width;
  scene.height = height;
  Draw draw;
  draw.topology = Topology::LineList;
  draw.state.line_width = line_width;
  scene.draws.push_back(std::move(draw));
  return scene;
}

// Wide lines that cross the view volume's sides, their ends a few pixels either side of the
// 64-row tile borders between workers: a clipped line is left out by a worker only when its
// clipped ends, widened by the line's margin, miss the worker's rows (walk_exact). A worker that
// left out a line whose quad reaches one of its rows would lose that row's pixels.
TEST(FastLines, ClippedLinesBesideAWorkersRows) {
  Scene scene = line_list_scene("clipped wide lines at tile borders", 200, 256, 7.0f);
  Draw& draw = scene.draws[0];
  for (int border = 1; border < 4; ++border) {
    for (int d = -6; d <= 6; ++d) {
      const float y = float(border * 64 + d) / 128.0f - 1.0f, z = 0.2f + 0.05f * float(d + 6);
      const float side = d % 2 == 0 ? -1.0f : 1.0f;  // alternately cut by the left and right planes
      draw.positions_clip.emplace_back(1.4f * side, y, z, 1.0f);
      draw.positions_clip.emplace_back(-0.6f * side, y + 0.01f * float(d), z + 0.1f, 1.0f);
    }
  }
  expect_fast_matches(scene, true, {1u, 2u, 3u, 4u});
}

// The same with enough lines for the reach phase (at least 4096), which clips the lines a clip
// plane cuts once for all workers and stores the rows of what is left (clipped_line_reach): lines
// beside every tile border, cut by the left and right planes and some wholly outside them, among
// lines clipped by the near and far planes, at 2-4 workers. The cut line's span without the
// line's margin fails it.
TEST(FastLines, ClippedLinesBesideAWorkersRowsInTheReachPhase) {
  Scene scene = line_list_scene("many clipped lines at tile borders", 200, 512, 3.0f);
  Draw& draw = scene.draws[0];
  fast_test::Random r(3);
  for (int n = 0; n < 4400; ++n) {
    const int border = 1 + int(r.below(7));
    const float y = (float(border * 64) + float(r.range(-8, 8))) / 256.0f - 1.0f;
    const float side = r.chance(0.5) ? -1.0f : 1.0f, z = float(r.range(-0.2, 1.2));
    const float reach = r.chance(0.1) ? 1.1f : -0.6f;  // a tenth wholly outside one plane
    draw.positions_clip.emplace_back(1.4f * side, y, z, 1.0f);
    draw.positions_clip.emplace_back(reach * side, y + float(r.range(-0.05, 0.05)), z + 0.1f, 1.0f);
  }
  expect_fast_matches(scene, true, {2u, 3u, 4u});
}

// A frame of lines whose rows would share the L1's sets (a width of 512 or 1,024 pixels) is drawn
// at a wider row pitch and packed at its width (frame_row_pitch); the thin rows then read and write
// each gathered step's rows as pairs (draw_pairs), except where a row's one pixel is the visit's
// last column (the frame's right edge, a worker's last tile). Lines of several widths, clipped at
// the left and right edges, on one to three workers: the exact path's bytes, with the pitch and
// without it. Frames of other widths (pairs at their own pitch), with triangles or of four
// samples keep their width.
TEST(FastRowPitch, LinesInFramesWhoseRowsShareL1SetsMatchExactPath) {
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    Scene scene = bench::lines_scene(1200, 512, seed);
    scene.name += " seed " + std::to_string(seed);
    Draw wide = bench::lines_scene(200, 512, seed + 10).draws[0];
    wide.state.line_width = float(seed) + 0.5f;  // runs of more than two columns: the row path
    for (glm::vec4& v : wide.positions_clip) v.x *= 1.3f;
    scene.draws.push_back(std::move(wide));
    EXPECT_EQ(cpu::fast::frame_row_pitch(scene), 528u);
    expect_fast_matches(scene, seed != 2, {1u, 2u, 3u});
    CpuOptions options;
    options.threads = 2;
    options.lavapipe = &lavapipe_releases().front();
    cpu::fast::FastConfig unpitched;
    unpitched.spread_pitch = false;
    EXPECT_TRUE(same_bytes(render_exact(scene, true), cpu::fast::render_fast(scene, options, unpitched)));
  }
  EXPECT_EQ(cpu::fast::frame_row_pitch(bench::lines_scene(30, 1024)), 1040u);
  EXPECT_EQ(cpu::fast::frame_row_pitch(bench::lines_scene(30, 4096)), 4096u);  // 130 MiB pitched: kept at its width
  EXPECT_EQ(cpu::fast::frame_row_pitch(bench::lines_scene(30, 500)), 500u);
  EXPECT_EQ(cpu::fast::frame_row_pitch(bench::msaa_grid_scene(12, 128)), 128u);
  Scene with_triangles = bench::lines_scene(300, 512);
  with_triangles.draws.push_back(bench::grid_scene(10, 512).draws[0]);
  EXPECT_EQ(cpu::fast::frame_row_pitch(with_triangles), 512u);
  expect_fast_matches(with_triangles, true, {2u});
  expect_fast_matches(bench::lines_scene(300, 500), true, {2u});
}

// The bench's scenes of lines by length and angle (lines_<L>px[_<A>deg], bench_scenes.hpp): 20,000
// lines of L px in a 512 px frame, each wholly inside it, at A degrees either way along the axis or
// at angles all round; a length or angle out of range, or another name, is a UsageError naming it.
// A small version on the fast path writes the exact path's bytes.
TEST(FastLines, BenchLineShapeScenes) {
  const Scene steep = bench::standard_bench_scene("lines_64px_80deg").scene;
  ASSERT_EQ(steep.width, 512u);
  ASSERT_EQ(steep.draws.size(), 1u);
  const std::vector<glm::vec4>& p = steep.draws[0].positions_clip;
  ASSERT_EQ(p.size(), 40000u);
  for (size_t i = 0; i < p.size(); i += 2) {
    const double dx = double(p[i + 1].x - p[i].x) * 256.0, dy = double(p[i + 1].y - p[i].y) * 256.0;  // pixels
    ASSERT_NEAR(std::hypot(dx, dy), 64.0, 1e-3) << "line " << i / 2;
    ASSERT_NEAR(std::abs(std::atan2(dy, dx)) * 180.0 / 3.141592653589793, dy >= 0 ? 80.0 : 100.0, 1e-3);
    for (const glm::vec4& v : {p[i], p[i + 1]}) {
      ASSERT_LT(std::abs(v.x), 1.0f);
      ASSERT_LT(std::abs(v.y), 1.0f);
    }
  }
  const Scene around = bench::standard_bench_scene("lines_16px").scene;
  const std::vector<glm::vec4>& any = around.draws[0].positions_clip;
  bool left = false, right = false, up = false, down = false;
  for (size_t i = 0; i < any.size(); i += 2) {
    left |= any[i + 1].x - any[i].x < -0.05f;
    right |= any[i + 1].x - any[i].x > 0.05f;
    down |= any[i + 1].y - any[i].y < -0.05f;
    up |= any[i + 1].y - any[i].y > 0.05f;
  }
  EXPECT_TRUE(left && right && up && down);
  for (const char* bad : {"lines_0px", "lines_257px", "lines_64px_181deg", "lines_99999px", "lines_px", "lines_64"})
    EXPECT_THROW(bench::standard_bench_scene(bad), UsageError) << bad;
  expect_fast_matches(bench::line_shape_scene(600, 40, 60.0, 128), true, {1u, 2u});
}

}  // namespace
}  // namespace rastercmp
