// Shared by tests/test_fast_*.cpp: seeded random scenes that exercise every state the fast path
// touches, and a byte-for-byte comparison of two results that names the first differing sample.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/render_fast.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp::fast_test {

struct RandomSceneSpec {
  bool allow_multisample = true;
  bool allow_lines = true;
  uint32_t max_side = 160;
  uint32_t max_primitives = 40;  // per draw
};

class Random {
 public:
  explicit Random(uint64_t seed) : rng_(seed) {}
  double unit() { return double(rng_() >> 11) * 0x1.0p-53; }  // [0, 1), library-independent
  double range(double lo, double hi) { return lo + (hi - lo) * unit(); }
  uint32_t below(uint32_t n) { return uint32_t(rng_() % n); }
  bool chance(double p) { return unit() < p; }

 private:
  std::mt19937_64 rng_;
};

inline glm::vec4 random_vertex(Random& r, int kind) {
  switch (kind) {
    case 0: {  // anywhere on screen, w = 1
      return {float(r.range(-1.1, 1.1)), float(r.range(-1.1, 1.1)), float(r.range(-0.1, 1.1)), 1.0f};
    }
    case 1: {  // perspective: w away from 1, some vertices outside the volume (clipping)
      const float w = float(r.range(0.2, 3.0));
      return {float(r.range(-1.6, 1.6)) * w, float(r.range(-1.6, 1.6)) * w, float(r.range(-0.3, 1.3)) * w, w};
    }
    default: {  // a snapped-grid-ish position: exact pixel centres and edges
      const float x = float(int(r.below(33)) - 16) / 16.0f, y = float(int(r.below(33)) - 16) / 16.0f;
      return {x, y, float(r.below(5)) / 4.0f, 1.0f};
    }
  }
}

inline Draw random_draw(Random& r, const RandomSceneSpec& spec) {
  Draw draw;
  const uint32_t topo = r.below(spec.allow_lines ? 6 : 4);
  draw.topology = topo == 0 || topo == 3 ? Topology::TriangleList
                  : topo == 1            ? Topology::TriangleStrip
                  : topo == 2            ? Topology::TriangleFan
                  : topo == 4            ? Topology::LineList
                                         : Topology::LineStrip;
  const int kind = int(r.below(3));
  const uint32_t primitives = 1 + r.below(spec.max_primitives);
  const bool tiny = r.chance(0.3);
  for (uint32_t p = 0; p < primitives + 2; ++p) {
    glm::vec4 v = random_vertex(r, kind);
    if (tiny && !draw.positions_clip.empty()) {  // triangles of a few pixels around the last vertex
      const glm::vec4& last = draw.positions_clip.back();
      v = glm::vec4(last.x + float(r.range(-0.05, 0.05)) * last.w, last.y + float(r.range(-0.05, 0.05)) * last.w,
                    last.z, last.w);
    }
    draw.positions_clip.push_back(v);
  }
  if (draw.topology == Topology::TriangleList) {
    while (draw.positions_clip.size() % 3) draw.positions_clip.pop_back();
  }
  if (r.chance(0.4)) {  // indexed: reuse vertices in a shuffled order
    const uint32_t n = uint32_t(draw.positions_clip.size());
    for (uint32_t k = 0; k < n + 3 * r.below(4); ++k) draw.indices.push_back(r.below(n));
    if (draw.topology == Topology::TriangleList) draw.indices.resize(draw.indices.size() / 3 * 3);
  }
  RasterState& s = draw.state;
  s.cull_mode = CullMode(r.below(4));
  s.front_face = FrontFace(r.below(2));
  s.line_width = float(1 + r.below(3));
  s.line_mode = r.chance(0.3) ? LineMode::Bresenham : LineMode::Default;
  s.depth.test_enable = !r.chance(0.1);
  s.depth.write_enable = !r.chance(0.2);
  s.depth.compare_op = r.chance(0.5) ? CompareOp::Less : CompareOp(r.below(8));
  if (r.chance(0.3)) {
    s.depth_bias = DepthBias{true, float(r.range(-4, 4)), float(r.range(-2, 2)),
                             r.chance(0.5) ? float(r.range(-0.01, 0.01)) : 0.0f};
  }
  s.depth_clamp = r.chance(0.2);
  if (r.chance(0.2)) s.depth_clip = r.chance(0.5);
  return draw;
}

inline Scene random_scene(uint64_t seed, const RandomSceneSpec& spec = {}) {
  Random r(seed);
  Scene scene;
  scene.name = "test.fast.random." + std::to_string(seed);
  scene.width = 16 + r.below(spec.max_side - 15);
  scene.height = 16 + r.below(spec.max_side - 15);
  scene.depth_format = DepthFormat(r.below(4));
  scene.depth_clear = r.chance(0.5) ? 1.0f : float(r.range(0.3, 1.0));
  scene.samples = spec.allow_multisample && r.chance(0.15) ? 4 : 1;
  if (r.chance(0.4)) {
    const float w = float(r.range(8, scene.width * 1.2)), h = float(r.range(8, scene.height * 1.2));
    const float mn = float(r.range(0, 0.5)), mx = float(r.range(0.5, 1));
    scene.viewport = Viewport{float(r.range(-10, scene.width * 0.5)),
                              float(r.range(-10, scene.height * 0.5)),
                              w,
                              r.chance(0.2) ? -h : h,
                              r.chance(0.2) ? mx : mn,
                              r.chance(0.2) ? mn : mx};
    if (scene.viewport->height < 0) scene.viewport->y += h;
  }
  if (r.chance(0.3)) {
    scene.scissor = Rect2D{int32_t(r.below(scene.width / 2)), int32_t(r.below(scene.height / 2)),
                           1 + r.below(scene.width), 1 + r.below(scene.height)};
  }
  const uint32_t draws = 1 + r.below(4);
  for (uint32_t d = 0; d < draws; ++d) scene.draws.push_back(random_draw(r, spec));
  return scene;
}

// Overlapping big quads over several draws: every compare op, write on and off, all formats,
// framebuffers whose sides are not multiples of the tile size; exercises the tile depth bounds
// and the fast clear.
inline Scene layered_scene(uint64_t seed) {
  Random r(seed);
  Scene scene;
  scene.name = "test.fast.layered." + std::to_string(seed);
  scene.width = 40 + r.below(200);
  scene.height = 40 + r.below(200);
  scene.depth_format = DepthFormat(1 + r.below(3));
  scene.depth_clear = r.chance(0.5) ? 1.0f : float(r.range(0, 1));
  const uint32_t draws = 2 + r.below(5);
  for (uint32_t d = 0; d < draws; ++d) {
    Draw draw;
    const uint32_t quads = 1 + r.below(4);
    for (uint32_t q = 0; q < quads; ++q) {
      const float x0 = float(r.range(-1.3, 0.2)), x1 = float(r.range(0.2, 1.3));
      const float y0 = float(r.range(-1.3, 0.2)), y1 = float(r.range(0.2, 1.3));
      const float z = float(r.range(-0.1, 1.1)), tilt_x = float(r.range(-0.2, 0.2)), tilt_y = float(r.range(-0.2, 0.2));
      const auto corner = [&](float x, float y) { return glm::vec4(x, y, z + tilt_x * x + tilt_y * y, 1.0f); };
      for (const glm::vec4& v :
           {corner(x0, y0), corner(x1, y0), corner(x1, y1), corner(x0, y0), corner(x1, y1), corner(x0, y1)})
        draw.positions_clip.push_back(v);
    }
    draw.state.depth.compare_op = r.chance(0.5) ? CompareOp::Less : CompareOp(r.below(8));
    draw.state.depth.write_enable = !r.chance(0.2);
    draw.state.depth.test_enable = !r.chance(0.1);
    draw.state.depth_clamp = r.chance(0.2);
    if (r.chance(0.2)) draw.state.depth_bias = DepthBias{true, float(r.range(-3, 3)), float(r.range(-1, 1)), 0.0f};
    scene.draws.push_back(std::move(draw));
  }
  if (r.chance(0.3))
    scene.viewport = Viewport{float(r.range(-20, 20)), float(r.range(-20, 20)), float(scene.width),
                              float(scene.height),     float(r.range(0, 0.3)),  float(r.range(0.7, 1))};
  return scene;
}

// A jittered grid of small triangles (cells of 0.6 to 7 pixels) as lists, strips or fans, with
// random depth state: the eight-wide set-up, its grid and kernel lanes, tile borders, row ends.
inline Scene small_mesh_scene(uint64_t seed) {
  Random r(seed);
  Scene scene;
  scene.name = "test.fast.small_mesh." + std::to_string(seed);
  scene.width = 33 + r.below(220);
  scene.height = 33 + r.below(220);
  scene.depth_format = DepthFormat(r.below(4));
  const float cell_px = float(r.range(0.6, 7.0));
  const uint32_t columns = std::min(uint32_t(float(scene.width) / cell_px) + 2, 300u);
  const uint32_t rows = std::min(uint32_t(float(scene.height) / cell_px) + 2, 300u);
  Draw draw;
  const float step_x = 2.2f / float(columns), step_y = 2.2f / float(rows);
  for (uint32_t j = 0; j <= rows; ++j)
    for (uint32_t i = 0; i <= columns; ++i) {
      const float x = -1.1f + step_x * (float(i) + float(r.range(-0.3, 0.3)));
      const float y = -1.1f + step_y * (float(j) + float(r.range(-0.3, 0.3)));
      draw.positions_clip.emplace_back(x, y, float(r.range(0.0, 1.0)), 1.0f);
    }
  const uint32_t topology = r.below(3);
  for (uint32_t j = 0; j < rows; ++j)
    for (uint32_t i = 0; i < columns; ++i) {
      const uint32_t v = j * (columns + 1) + i;
      for (uint32_t k : {v, v + 1, v + columns + 2, v, v + columns + 2, v + columns + 1}) draw.indices.push_back(k);
    }
  if (topology == 1) draw.topology = Topology::TriangleStrip;  // the same indices, read as a strip
  if (topology == 2) {  // two rows of cells: over the whole mesh a fan's triangles span the frame
    draw.topology = Topology::TriangleFan;
    draw.indices.resize(std::min<size_t>(draw.indices.size(), 12 * columns));
  }
  draw.state.cull_mode = CullMode(r.below(4));
  draw.state.front_face = FrontFace(r.below(2));
  draw.state.depth.compare_op = r.chance(0.5) ? CompareOp::Less : CompareOp(r.below(8));
  draw.state.depth.write_enable = !r.chance(0.2);
  draw.state.depth_clamp = r.chance(0.2);
  scene.draws.push_back(draw);
  draw.state.depth.compare_op = CompareOp(r.below(8));  // a second pass over the same mesh
  scene.draws.push_back(std::move(draw));
  if (r.chance(0.3))
    scene.scissor = Rect2D{int32_t(r.below(40)), int32_t(r.below(40)), 20 + r.below(200), 20 + r.below(200)};
  return scene;
}

// Scattered triangles of 8 to 64 px (the row-column kernel's, tile_kernel_avx2.cpp), some across
// tile borders and the framebuffer's edges, over framebuffers whose width is no multiple of 8
// (spans past the row's end), with random depth state per draw.
inline Scene mid_triangle_scene(uint64_t seed) {
  Random r(seed);
  Scene scene;
  scene.name = "test.fast.mid_triangles." + std::to_string(seed);
  scene.width = 60 + r.below(200);
  scene.height = 60 + r.below(200);
  scene.depth_format = DepthFormat(r.below(4));
  scene.depth_clear = r.chance(0.5) ? 1.0f : float(r.range(0.3, 1.0));
  const uint32_t draws = 1 + r.below(3);
  for (uint32_t d = 0; d < draws; ++d) {
    Draw draw;
    const uint32_t triangles = 20 + r.below(200);
    for (uint32_t k = 0; k < triangles; ++k) {
      const float size_px = float(r.range(8, 64));
      const float sx = 2.0f * size_px / float(scene.width), sy = 2.0f * size_px / float(scene.height);
      const float cx = float(r.range(-1.1, 1.1)), cy = float(r.range(-1.1, 1.1));
      for (int v = 0; v < 3; ++v)
        draw.positions_clip.emplace_back(cx + sx * float(r.range(-0.5, 0.5)), cy + sy * float(r.range(-0.5, 0.5)),
                                         float(r.range(0.0, 1.0)), 1.0f);
    }
    draw.state.cull_mode = CullMode(r.below(4));
    draw.state.depth.compare_op = r.chance(0.5) ? CompareOp::Less : CompareOp(r.below(8));
    draw.state.depth.write_enable = !r.chance(0.2);
    draw.state.depth.test_enable = !r.chance(0.1);
    draw.state.depth_clamp = r.chance(0.2);
    if (r.chance(0.2)) draw.state.depth_bias = DepthBias{true, float(r.range(-3, 3)), float(r.range(-1, 1)), 0.0f};
    scene.draws.push_back(std::move(draw));
  }
  if (r.chance(0.3))
    scene.scissor = Rect2D{int32_t(r.below(40)), int32_t(r.below(40)), 20 + r.below(200), 20 + r.below(200)};
  return scene;
}

// `triangles` small triangles whose set-up meets a denormal (z 0 and 1.5e-31, constant bias -0.5 on
// d32_sfloat: r * c = -2^-127), the first with a vertex outside the view volume, so the draw's chunk
// takes the draw pipeline (docs/lavapipe-rules.md §7.11). `then_unclipped`: an indexed list whose
// second chunk (4 more triangles) has no clipped vertex.
inline Scene denormal_setup_batch_scene(uint32_t triangles, bool then_unclipped) {
  Scene scene;
  scene.name = "test.denormal_setup_batch";
  scene.width = scene.height = 64;
  Draw draw;
  const auto clip = [](float x, float y, float z) { return glm::vec4(x / 32.0f - 1.0f, y / 32.0f - 1.0f, z, 1.0f); };
  draw.positions_clip = {{-1.1f, -0.9f, 0.0f, 1.0f}, {-0.5f, -0.9f, 1.5e-31f, 1.0f}, {-0.95f, -0.45f, 0.0f, 1.0f}};
  const uint32_t total = then_unclipped ? 345 : triangles;
  for (uint32_t i = 1; i < total; ++i) {
    const float x = float(i % 36) * 1.75f + 1.0f, y = float(i / 36) * 5.5f + 8.0f;
    draw.positions_clip.push_back(clip(x, y, 0.0f));
    draw.positions_clip.push_back(clip(x + 1.7f, y + 0.3f, 1.5e-31f));
    draw.positions_clip.push_back(clip(x + 0.2f, y + 1.6f, 0.0f));
  }
  if (then_unclipped)
    for (uint32_t k = 0; k < draw.positions_clip.size(); ++k) draw.indices.push_back(k);
  draw.state.depth_bias = DepthBias{true, -0.5f, 0.001f, 0.0f};
  scene.draws.push_back(std::move(draw));
  return scene;
}

// Renders with the exact path (threads = 0).
inline RenderResult render_exact(const Scene& scene, bool fma,
                                 const LavapipeRelease& release = lavapipe_releases().front()) {
  CpuOptions options;
  options.fma = fma;
  options.lavapipe = &release;
  options.threads = 0;
  return render_cpu(scene, options);
}

// The fast path's instruction sets, each with its own kernels: the scalar twins, AVX2, and
// AVX2 with the AVX-512 set-up and window compositor.
enum class FastIsa { Scalar, Avx2, Avx512 };

inline const char* isa_name(FastIsa isa) {
  return isa == FastIsa::Scalar ? "scalar" : isa == FastIsa::Avx2 ? "avx2" : "avx512";
}

// Every variant this host runs (the scalar one always).
inline std::vector<FastIsa> host_isas() {
  std::vector<FastIsa> isas{FastIsa::Scalar};
  if (cpu::fast::host_has_avx2_fma()) isas.push_back(FastIsa::Avx2);
  if (cpu::fast::host_has_avx512()) isas.push_back(FastIsa::Avx512);
  return isas;
}

// The variant render_cpu_fast picks on this host.
inline FastIsa best_isa() { return host_isas().back(); }

inline RenderResult render_fast(const Scene& scene, bool fma, uint32_t threads, FastIsa isa,
                                const LavapipeRelease& release = lavapipe_releases().front()) {
  CpuOptions options;
  options.fma = fma;
  options.lavapipe = &release;
  options.threads = threads;
  cpu::fast::FastConfig config;
  config.allow_avx2 = isa != FastIsa::Scalar;
  config.allow_avx512 = isa == FastIsa::Avx512;
  config.every_thread = true;  // the workers really split the rows, even on scenes one worker would take alone
  return cpu::fast::render_fast(scene, options, config);
}

// Identical owner and depth bytes; on failure names the first differing sample.
inline ::testing::AssertionResult same_bytes(const RenderResult& expected, const RenderResult& actual) {
  if (expected.width != actual.width || expected.height != actual.height || expected.samples != actual.samples)
    return ::testing::AssertionFailure() << "size differs";
  const auto first_difference = [&](const PixelBuffer& a, const PixelBuffer& b,
                                    const char* what) -> ::testing::AssertionResult {
    if (a.size() != b.size()) return ::testing::AssertionFailure() << what << " sizes differ";
    size_t count = 0, first = a.size();
    for (size_t i = 0; i < a.size(); ++i)
      if (a[i] != b[i]) {
        if (count++ == 0) first = i;
      }
    if (count == 0) return ::testing::AssertionSuccess();
    const size_t pixel = first / expected.samples;
    return ::testing::AssertionFailure() << count << " " << what
                                         << " samples differ; first at x=" << pixel % expected.width
                                         << " y=" << pixel / expected.width << " sample " << first % expected.samples
                                         << ": expected 0x" << std::hex << a[first] << ", got 0x" << b[first];
  };
  ::testing::AssertionResult owner = first_difference(expected.owner, actual.owner, "owner");
  if (!owner) return owner;
  return first_difference(expected.depth_raw, actual.depth_raw, "depth");
}

// Every fast variant against the exact result: the scalar twins and the host's best kernels at
// every thread count; on an AVX-512 host the AVX2 kernels too, at 2 threads (what an AVX2 host's
// render_cpu_fast runs; once is enough to keep them honest, and the suite's time counts in CI).
inline void expect_fast_matches(const Scene& scene, bool fma,
                                std::initializer_list<uint32_t> thread_counts = {1u, 2u}) {
  const RenderResult exact = render_exact(scene, fma);
  for (const uint32_t threads : thread_counts) {
    for (const FastIsa isa : host_isas()) {
      if (isa != best_isa() && isa != FastIsa::Scalar && threads != 2) continue;
      SCOPED_TRACE(scene.name + " threads=" + std::to_string(threads) + " " + isa_name(isa) +
                   (fma ? " fma" : " no-fma"));
      EXPECT_TRUE(same_bytes(exact, render_fast(scene, fma, threads, isa)));
    }
  }
}

}  // namespace rastercmp::fast_test
