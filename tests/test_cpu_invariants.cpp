// CPU-only invariants of the exact path, checked with random cases (rapidcheck): tessellations
// whose triangles share edges exactly cover every sample inside them exactly once — the top-left
// rule's promise ("exactly one of the polygons", primsrast.adoc) — on odd framebuffer sizes, with
// random vertex order, and with clipping where the shape leaves the view volume.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "cpu_raster/exact/render_targets.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu {
namespace {

struct Point {
  float x, y;  // framebuffer pixels
};

// How many primitives cover each sample: every primitive is rasterized alone into a cleared target
// (the exact path's own front end and rasterizer) and its covered samples are counted, once per
// primitive. The pieces of one clipped primitive may overlap: its polygon, convex as clipped, can
// turn concave when its vertices are snapped, and then two triangles of its fan cover the same
// samples (make properties, session 13: a clip at y = 21 made vertices 0.024 px apart, one snapped
// to the other side of the fan's diagonal). That is lavapipe's clipper and set-up, which the exact
// path reproduces; the tie rule's promise is about different primitives.
std::vector<int> coverage_counts(const Scene& scene) {
  const FrameContext frame = make_frame_context(scene, true, {});
  RenderTargets alone = make_render_targets(scene);
  std::vector<int> counts(alone.owner.size(), 0);
  std::vector<uint32_t> counted_for(alone.owner.size(), kOwnerBackground);  // the primitive last counted
  for (uint32_t d = 0; d < scene.draws.size(); ++d) {
    const DepthTestState depth = make_depth_test_state(scene, scene.draws[d], frame.viewport, true);
    run_front_end(frame, d, [&](const PrimitiveOutcome& o) {
      if (!o.rasterized()) return;
      rasterize_primitive(o.raster, depth, alone);
      for (size_t i = 0; i < alone.owner.size(); ++i) {
        if (alone.owner[i] != kOwnerBackground && counted_for[i] != alone.owner[i]) {
          ++counts[i];
          counted_for[i] = alone.owner[i];
        }
        alone.owner[i] = kOwnerBackground;
      }
    });
  }
  return counts;
}

Scene make_scene(uint32_t width, uint32_t height, uint32_t samples) {
  Scene scene;
  scene.width = width;
  scene.height = height;
  scene.samples = samples;
  scene.depth_format = DepthFormat::None;
  return scene;
}

glm::vec4 to_clip(const Scene& scene, Point p) {
  return {2 * p.x / float(scene.width) - 1, 2 * p.y / float(scene.height) - 1, 0.5f, 1};
}

// Uniform over [lo, hi) whatever the current size (rapidcheck scales inRange with it).
int uniform_int(int lo, int hi) { return *rc::gen::resize(rc::kNominalSize, rc::gen::inRange(lo, hi)); }
uint32_t odd_size() { return uint32_t(uniform_int(2, 20)) * 2 + 1; }
uint32_t sample_count() { return *rc::gen::element(1u, 4u); }
float random_float(float lo, float hi) { return lo + (hi - lo) * float(uniform_int(0, 1 << 16)) / 65536.0f; }

// Appends the triangle with a random rotation of its vertices and a random winding.
void add_triangle(const Scene& scene, Draw& draw, Point a, Point b, Point c) {
  std::vector<Point> v = {a, b, c};
  std::rotate(v.begin(), v.begin() + uniform_int(0, 3), v.end());
  if (*rc::gen::arbitrary<bool>()) std::swap(v[1], v[2]);
  for (const Point& p : v) draw.positions_clip.push_back(to_clip(scene, p));
}

// A sample position in framebuffer pixels.
Point sample_position(const Scene& scene, uint32_t x, uint32_t y, uint32_t s) {
  if (scene.samples == 1) return {float(x) + 0.5f, float(y) + 0.5f};
  const SampleOffset& o = kStandardSamples4x[s];
  return {float(x) + o.x, float(y) + o.y};
}

// Every sample is covered at most once, and exactly once where `inside` says it is well inside.
template <class Inside>
void check_exactly_once(const Scene& scene, Inside inside) {
  const std::vector<int> counts = coverage_counts(scene);
  int covered = 0;
  for (uint32_t y = 0; y < scene.height; ++y)
    for (uint32_t x = 0; x < scene.width; ++x)
      for (uint32_t s = 0; s < scene.samples; ++s) {
        const int n = counts[(size_t(y) * scene.width + x) * scene.samples + s];
        RC_ASSERT(n <= 1);
        if (inside(sample_position(scene, x, y, s))) RC_ASSERT(n == 1);
        covered += n;
      }
  RC_TAG(covered > 0 ? "covers samples" : "covers nothing");
}

// A jittered grid of quads, each split along a random diagonal, over a rectangle that may extend
// past the framebuffer (then the triangles are clipped).
RC_GTEST_PROP(CpuInvariants, TessellatedRectangleCoversEachSampleOnce, ()) {
  Scene scene = make_scene(odd_size(), odd_size(), sample_count());
  // Half the cases put every vertex on the half-pixel grid: shared edges then run through pixel
  // centres and the tie-break decides them.
  const bool on_centres = *rc::gen::arbitrary<bool>();
  const auto snap = [&](float v) { return on_centres ? std::round(v * 2) / 2 : v; };
  const float x0 = snap(random_float(-6, 4)), y0 = snap(random_float(-6, 4));
  const float x1 = snap(x0 + random_float(4, float(scene.width) + 6)),
              y1 = snap(y0 + random_float(4, float(scene.height) + 6));
  const int nx = uniform_int(1, 7), ny = uniform_int(1, 7);
  std::vector<Point> grid;
  // Inner vertices move by up to 0.2 of a cell along each axis, which keeps every quad convex (a
  // corner stays on its side of its neighbours' diagonal; at 0.3 a quad can fold and its two
  // triangles overlap). The half-pixel grid gets no jitter: snapping a jittered grid could fold it.
  const float jitter = on_centres ? 0.0f : 0.2f;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const bool inner_x = i > 0 && i<nx, inner_y = j> 0 && j < ny;
      const float jx = inner_x ? random_float(-jitter, jitter) : 0, jy = inner_y ? random_float(-jitter, jitter) : 0;
      grid.push_back({i == 0    ? x0
                      : i == nx ? x1
                                : snap(x0 + (x1 - x0) * (float(i) + jx) / float(nx)),
                      j == 0    ? y0
                      : j == ny ? y1
                                : snap(y0 + (y1 - y0) * (float(j) + jy) / float(ny))});
    }
  Draw draw;
  draw.state.depth.test_enable = false;
  const auto at = [&](int i, int j) { return grid[size_t(j * (nx + 1) + i)]; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Point a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (*rc::gen::arbitrary<bool>()) {
        add_triangle(scene, draw, a, b, c);
        add_triangle(scene, draw, a, c, d);
      } else {
        add_triangle(scene, draw, a, b, d);
        add_triangle(scene, draw, b, c, d);
      }
    }
  scene.draws.push_back(draw);
  const float margin = 1.0f / 64;  // window positions of odd-sized framebuffers are rounded
  check_exactly_once(
      scene, [&](Point p) { return p.x > x0 + margin && p.x < x1 - margin && p.y > y0 + margin && p.y < y1 - margin; });
}

// `count` points on an ellipse in increasing angle, one in each of `count` equal sectors (so for
// count >= 4 no gap reaches half a turn and the centre is inside): a convex polygon.
std::vector<Point> convex_ring(float cx, float cy, float rx, float ry, int count) {
  std::vector<Point> ring;
  for (int k = 0; k < count; ++k) {
    const float a = 2 * std::numbers::pi_v<float> * (float(k) + random_float(0, 0.9f)) / float(count);
    ring.push_back({cx + rx * std::cos(a), cy + ry * std::sin(a)});
  }
  return ring;
}

// Inside the convex polygon `ring` (counter-clockwise in angle order) by at least `margin` px.
bool inside_convex(const std::vector<Point>& ring, Point p, float margin) {
  for (size_t i = 0; i < ring.size(); ++i) {
    const Point a = ring[i], b = ring[(i + 1) % ring.size()];
    const float ex = b.x - a.x, ey = b.y - a.y;
    const float cross = ex * (p.y - a.y) - ey * (p.x - a.x);
    if (cross < margin * std::hypot(ex, ey)) return false;
  }
  return true;
}

RC_GTEST_PROP(CpuInvariants, FanAroundASharedVertexCoversEachSampleOnce, ()) {
  Scene scene = make_scene(odd_size(), odd_size(), sample_count());
  const float cx = random_float(0, float(scene.width)), cy = random_float(0, float(scene.height));
  const std::vector<Point> ring = convex_ring(cx, cy, random_float(2, 30), random_float(2, 30), uniform_int(4, 24));
  const Point hub{cx, cy};
  Draw draw;
  draw.state.depth.test_enable = false;
  for (size_t i = 0; i < ring.size(); ++i) add_triangle(scene, draw, hub, ring[i], ring[(i + 1) % ring.size()]);
  scene.draws.push_back(draw);
  check_exactly_once(scene, [&](Point p) { return inside_convex(ring, p, 1.0f / 64); });
}

// A random convex polygon triangulated by random diagonals (ear removal in random order).
RC_GTEST_PROP(CpuInvariants, TriangulatedConvexPolygonCoversEachSampleOnce, ()) {
  Scene scene = make_scene(odd_size(), odd_size(), sample_count());
  const std::vector<Point> ring =
      convex_ring(random_float(-4, float(scene.width) + 4), random_float(-4, float(scene.height) + 4),
                  random_float(2, 40), random_float(2, 40), uniform_int(3, 16));
  Draw draw;
  draw.state.depth.test_enable = false;
  std::vector<Point> rest = ring;
  while (rest.size() > 3) {
    const size_t k = size_t(uniform_int(0, int(rest.size())));
    add_triangle(scene, draw, rest[(k + rest.size() - 1) % rest.size()], rest[k], rest[(k + 1) % rest.size()]);
    rest.erase(rest.begin() + std::ptrdiff_t(k));
  }
  add_triangle(scene, draw, rest[0], rest[1], rest[2]);
  scene.draws.push_back(draw);
  check_exactly_once(scene, [&](Point p) { return inside_convex(ring, p, 1.0f / 64); });
}

// The case behind coverage_counts' once per primitive: a triangle clipped at the frame's bottom
// (y = 21) into A, B, C, D with B and C 0.024 px apart; snapped, B lies on the other side of the
// fan's diagonal A-C, so the fan's pieces (A, B, C) and (A, C, D) both cover sample 3 of pixel
// (12, 18). Either count alone would hide a change of the clipper, the fan or the snapping.
TEST(CpuInvariants, ClippedPolygonConcaveAfterSnappingCoversASampleTwice) {
  Scene scene = make_scene(37, 21, 4);
  Draw draw;
  draw.state.depth.test_enable = false;
  for (const Point p : {Point{12.9831f, 8.58399f}, Point{12.5512f, 20.9754f}, Point{11.8935f, 28.7966f}})
    draw.positions_clip.push_back(to_clip(scene, p));
  scene.draws.push_back(draw);
  const FrameContext frame = make_frame_context(scene, true, {});
  RenderTargets alone = make_render_targets(scene);
  const size_t probe = (size_t(18) * scene.width + 12) * scene.samples + 3;
  int pieces = 0, covering = 0;
  run_front_end(frame, 0, [&](const PrimitiveOutcome& o) {
    if (!o.rasterized()) return;
    ++pieces;
    std::fill(alone.owner.begin(), alone.owner.end(), kOwnerBackground);
    rasterize_primitive(o.raster, make_depth_test_state(scene, scene.draws[0], frame.viewport, true), alone);
    covering += alone.owner[probe] != kOwnerBackground;
  });
  EXPECT_EQ(pieces, 2);
  EXPECT_EQ(covering, 2);
  EXPECT_EQ(coverage_counts(scene)[probe], 1);
}

}  // namespace
}  // namespace rastercmp::cpu
