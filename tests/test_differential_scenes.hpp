// Seeded random scenes for the differential tests. Each generator covers one family of cases from
// docs/lavapipe-rules.md ("Empirical verification"): grid-aligned ties, perspective, clipping in
// x/y/z, slivers, far from the origin, depth bias with culling, depth clamp with a scissor,
// multi-triangle draws, lines in both modes, strips and fans, 4x coverage, LESS compares.
// Most draws hold one primitive, so owner ids name the primitive and the driver's per-draw
// "pipelined" flag is exercised per primitive; the multi-triangle family groups 16 per draw.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "tests/test_differential_support.hpp"

namespace rastercmp::differential {

inline std::string scene_name(const char* family, uint32_t seed) {
  return fmt::format("rastercmp.differential.{}.seed{}", family, seed);
}

// A framebuffer coordinate on the 1/256 grid, often on a pixel centre or a pixel corner.
inline float grid_coordinate(Random& rng, float centre, int spread) {
  const float base = std::floor(centre) + float(rng.integer(-spread, spread));
  switch (rng.integer(0, 2)) {
    case 0: return base + 0.5f;
    case 1: return base;
    default: return base + float(rng.integer(0, 255)) / 256.0f;
  }
}

// Triangles with vertices on the 1/256 grid (power-of-two framebuffer, so window positions are
// exact), many on pixel centres: edges through sample points, the tie-break cases.
inline Scene grid_triangles(uint32_t seed, int fine_grid_bits = 8) {
  Random rng(seed);
  Scene scene = make_scene(scene_name("grid", seed), 128, 64, format_for(seed));
  const float step = 1.0f / float(1 << fine_grid_bits);
  for (int d = 0; d < 200; ++d) {
    Draw draw;
    draw.state = always_state();
    const float cx = rng.uniform(-2, 130), cy = rng.uniform(-2, 66);
    const int spread = rng.chance(0.5f) ? 6 : 40;
    for (int k = 0; k < 3; ++k) {
      float x = grid_coordinate(rng, cx, spread), y = grid_coordinate(rng, cy, spread);
      if (fine_grid_bits > 8) {  // odd multiples of 1/512: exact rounding ties when snapped
        x += step * float(rng.integer(0, 1));
        y += step * float(rng.integer(0, 1));
      }
      draw.positions_clip.push_back(clip_from_window(x, y, rng.uniform(0, 1), scene));
    }
    scene.draws.push_back(draw);
  }
  return scene;
}

// Random clip-space triangle: w in [w_lo, w_hi], x/y within `reach`*w, z within [z_lo, z_hi]*w.
inline std::vector<glm::vec4> random_clip_triangle(Random& rng, float reach, float z_lo, float z_hi, float w_lo,
                                                   float w_hi) {
  std::vector<glm::vec4> v;
  const float cx = rng.uniform(-reach, reach), cy = rng.uniform(-reach, reach);
  const float size = rng.chance(0.5f) ? 0.15f : 1.2f;
  for (int k = 0; k < 3; ++k) {
    float w = rng.uniform(w_lo, w_hi);
    if (std::fabs(w) < 0.05f) w = 0.05f;
    const float x = cx + rng.uniform(-size, size), y = cy + rng.uniform(-size, size);
    v.push_back({x * std::fabs(w), y * std::fabs(w), rng.uniform(z_lo, z_hi) * std::fabs(w), w});
  }
  return v;
}

inline Scene clip_space_triangles(const char* family, uint32_t seed, float reach, float z_lo, float z_hi, float w_lo,
                                  float w_hi) {
  Random rng(seed);
  Scene scene = make_scene(scene_name(family, seed), 83, 71, format_for(seed));
  for (int d = 0; d < 200; ++d) {
    Draw draw;
    draw.state = always_state();
    draw.positions_clip = random_clip_triangle(rng, reach, z_lo, z_hi, w_lo, w_hi);
    scene.draws.push_back(draw);
  }
  return scene;
}

// Perspective triangles inside the view volume.
inline Scene perspective_triangles(uint32_t seed) {
  return clip_space_triangles("perspective", seed, 0.8f, 0, 1, 0.4f, 3);
}

// Triangles that need clipping against x, y and z, including vertices behind the eye (w < 0).
inline Scene clipped_triangles(uint32_t seed) {
  return clip_space_triangles("clipped", seed, 1.6f, -0.6f, 1.6f, -0.6f, 3);
}

// Slivers: a long edge and a third vertex a tiny distance from its line.
inline Scene sliver_triangles(uint32_t seed) {
  Random rng(seed);
  Scene scene = make_scene(scene_name("sliver", seed), 83, 71, format_for(seed));
  for (int d = 0; d < 200; ++d) {
    Draw draw;
    draw.state = always_state();
    draw.state.cull_mode = rng.pick(std::vector<CullMode>{CullMode::None, CullMode::Back, CullMode::Front});
    const float x0 = rng.uniform(-5, 88), y0 = rng.uniform(-5, 76);
    const float x1 = rng.uniform(-5, 88), y1 = rng.uniform(-5, 76);
    const float t = rng.uniform(0, 1), offset = std::ldexp(rng.uniform(-1, 1), -rng.integer(2, 20));
    const float len = std::hypot(x1 - x0, y1 - y0) + 1e-3f;
    const float x2 = x0 + t * (x1 - x0) - offset * (y1 - y0) / len, y2 = y0 + t * (y1 - y0) + offset * (x1 - x0) / len;
    for (const auto& [x, y] : {std::pair{x0, y0}, std::pair{x1, y1}, std::pair{x2, y2}})
      draw.positions_clip.push_back(clip_from_window(x, y, rng.uniform(0, 1), scene, rng.uniform(0.5f, 2)));
    scene.draws.push_back(draw);
  }
  return scene;
}

// A large framebuffer: small and medium triangles far from the origin, where a0 (extrapolated to
// the origin) loses precision.
inline Scene far_triangles(uint32_t seed) {
  Random rng(seed);
  Scene scene = make_scene(scene_name("far", seed), 2048, 1536, format_for(seed));
  for (int d = 0; d < 150; ++d) {
    Draw draw;
    draw.state = always_state();
    const float cx = rng.uniform(0, 2048), cy = rng.uniform(0, 1536), size = rng.chance(0.5f) ? 6 : 120;
    for (int k = 0; k < 3; ++k)
      draw.positions_clip.push_back(clip_from_window(cx + rng.uniform(-size, size), cy + rng.uniform(-size, size),
                                                     rng.uniform(0, 1), scene, rng.uniform(0.5f, 2)));
    scene.draws.push_back(draw);
  }
  return scene;
}

// Depth bias (constant, slope, clamp) with every cull mode and both front faces.
inline Scene bias_cull_triangles(uint32_t seed) {
  Random rng(seed);
  Scene scene = clip_space_triangles("bias_cull", seed, 1.2f, -0.2f, 1.2f, 0.3f, 3);
  // Eight bias settings per scene, each draw picking one: lavapipe compiles a set-up function per
  // distinct setting (llvmpipe's set-up variant holds the factors), about 10 ms each.
  std::vector<DepthBias> settings(8);
  for (DepthBias& bias : settings) {
    bias.enable = true;
    bias.constant_factor = rng.chance(0.2f) ? 0.0f : rng.uniform(-40, 40);
    bias.slope_factor = rng.chance(0.2f) ? 0.0f : rng.uniform(-3, 3);
    bias.clamp = rng.pick(std::vector<float>{0.0f, 0.0f, 1e-4f, -1e-4f, 0.01f, -0.01f});
  }
  for (Draw& draw : scene.draws) {
    draw.state.cull_mode = rng.pick(std::vector<CullMode>{CullMode::None, CullMode::Back, CullMode::Front});
    draw.state.front_face = rng.chance(0.5f) ? FrontFace::Clockwise : FrontFace::CounterClockwise;
    draw.state.depth_bias = rng.pick(settings);
  }
  return scene;
}

// Depth clamp (depth clip off or on) with a scissor and a narrowed, sometimes inverted, depth range.
inline Scene clamp_scissor_triangles(uint32_t seed) {
  Random rng(seed);
  Scene scene = clip_space_triangles("clamp_scissor", seed, 1.3f, -1.0f, 2.0f, 0.3f, 3);
  scene.scissor =
      Rect2D{rng.integer(0, 30), rng.integer(0, 30), uint32_t(rng.integer(10, 60)), uint32_t(rng.integer(10, 60))};
  Viewport viewport = scene.effective_viewport();
  viewport.min_depth = rng.uniform(0, 1);
  viewport.max_depth = rng.uniform(0, 1);
  scene.viewport = viewport;
  for (Draw& draw : scene.draws) {
    draw.state.depth_clamp = true;
    if (rng.chance(0.3f)) draw.state.depth_clip = rng.chance(0.5f);
  }
  return scene;
}

// Draws of 16 triangles each, with clipping, culling and slivers: the per-draw pipeline path and
// its float cull (docs/lavapipe-rules.md §2.6).
inline Scene multi_triangle_draws(uint32_t seed) {
  Random rng(seed);
  Scene scene = make_scene(scene_name("multi", seed), 83, 71, format_for(seed));
  for (int d = 0; d < 12; ++d) {
    Draw draw;
    draw.state = always_state();
    draw.state.cull_mode = rng.pick(std::vector<CullMode>{CullMode::None, CullMode::Back, CullMode::Front});
    draw.state.front_face = rng.chance(0.5f) ? FrontFace::Clockwise : FrontFace::CounterClockwise;
    for (int t = 0; t < 16; ++t) {
      std::vector<glm::vec4> tri = random_clip_triangle(rng, rng.chance(0.3f) ? 1.5f : 0.8f, 0, 1, 0.5f, 2);
      if (rng.chance(0.25f)) tri[2] = tri[0] + (tri[1] - tri[0]) * rng.uniform(0, 1) + glm::vec4(1e-5f, 0, 0, 0);
      draw.positions_clip.insert(draw.positions_clip.end(), tri.begin(), tri.end());
    }
    scene.draws.push_back(draw);
  }
  return scene;
}

// Lines of width 1 to 6 in one mode, some clipped, some with depth bias on (which lines ignore).
inline Scene line_scene(uint32_t seed, LineMode mode, uint32_t samples = 1) {
  Random rng(seed);
  Scene scene = make_scene(scene_name(mode == LineMode::Bresenham ? "lines_bresenham" : "lines_rectangular", seed), 83,
                           71, format_for(seed));
  scene.samples = samples;
  if (samples > 1 && seed % 2 == 0)  // the multisample scissor planes of lines
    scene.scissor =
        Rect2D{rng.integer(1, 30), rng.integer(1, 30), uint32_t(rng.integer(8, 50)), uint32_t(rng.integer(8, 40))};
  for (int d = 0; d < 200; ++d) {
    Draw draw;
    draw.state = always_state();
    draw.topology = rng.chance(0.8f) ? Topology::LineList : Topology::LineStrip;
    draw.state.line_mode = mode;
    draw.state.line_width = rng.chance(0.5f) ? float(rng.integer(1, 6)) : rng.uniform(1, 6);
    if (rng.chance(0.2f)) {
      draw.state.depth_bias.enable = true;
      draw.state.depth_bias.constant_factor = 8;
      draw.state.depth_bias.slope_factor = 1;
    }
    const float reach = rng.chance(0.3f) ? 1.4f : 0.9f, length = rng.chance(0.5f) ? 0.1f : 1.0f;
    const float cx = rng.uniform(-reach, reach), cy = rng.uniform(-reach, reach);
    const int vertices = draw.topology == Topology::LineList ? 2 : 3;
    for (int k = 0; k < vertices; ++k) {
      const float w = rng.uniform(0.5f, 2);
      const float x = rng.chance(0.3f) ? std::round((cx + rng.uniform(-length, length)) * 41.5f) / 41.5f
                                       : cx + rng.uniform(-length, length);
      draw.positions_clip.push_back({x * w, (cy + rng.uniform(-length, length)) * w, rng.uniform(-0.2f, 1.2f) * w, w});
    }
    scene.draws.push_back(draw);
  }
  return scene;
}

// One Bresenham line draw from window position (x1, y1) to (x2, y2), random depths.
inline void add_bresenham_line(Scene& scene, Random& rng, float width, float x1, float y1, float x2, float y2) {
  Draw draw;
  draw.state = always_state();
  draw.topology = Topology::LineList;
  draw.state.line_mode = LineMode::Bresenham;
  draw.state.line_width = width;
  draw.positions_clip.push_back(clip_from_window(x1, y1, rng.uniform(0, 1), scene));
  draw.positions_clip.push_back(clip_from_window(x2, y2, rng.uniform(0, 1), scene));
  scene.draws.push_back(draw);
}

// Wide Bresenham lines, y-major and x-major, starting exactly on a pixel centre (the diamond-exit
// start tests at y1diff == 0, docs/lavapipe-rules.md §5.4). The far end is on an odd 1/256 step, so the
// side edges do not pass through sample points.
inline Scene centred_bresenham_lines(uint32_t seed) {
  Random rng(seed);
  Scene scene = make_scene(scene_name("lines_bresenham_centred", seed), 128, 64, format_for(seed));
  for (int d = 0; d < 60; ++d) {
    const float width = float(rng.integer(1, 6));
    const float x1 = float(rng.integer(8, 119)) + 0.5f, y1 = float(rng.integer(8, 55)) + 0.5f;
    const float major = float(rng.integer(6, 30)) * (rng.chance(0.5f) ? 1.0f : -1.0f);
    const float minor = rng.uniform(-0.9f, 0.9f) * std::fabs(major);
    const float odd_step = float(2 * rng.integer(0, 127) + 1) / 256.0f;
    const bool y_major = rng.chance(0.5f);
    const float x2 = std::floor(x1 + (y_major ? minor : major)) + odd_step;
    const float y2 = std::floor(y1 + (y_major ? major : minor)) + odd_step;
    add_bresenham_line(scene, rng, width, x1, y1, x2, y2);
  }
  return scene;
}

// Wide and thin Bresenham lines between lattice points: each end on a pixel centre or a pixel
// corner, slopes small rationals that are mostly not powers of two (1/3, 2/5, ...), every
// direction. The side edges pass exactly through samples, so any half-pixel end shift that the
// model decides differently from the driver tilts them and moves a row (docs/lavapipe-rules.md §5.4).
inline Scene lattice_bresenham_lines(uint32_t seed) {
  Random rng(seed);
  Scene scene = make_scene(scene_name("lines_bresenham_lattice", seed), 128, 96, format_for(seed));
  for (int d = 0; d < 60; ++d) {
    const float width = float(rng.integer(1, 6));
    const float corner = rng.chance(0.25f) ? 0.0f : 0.5f;
    const float x1 = float(rng.integer(6, 121)) + corner, y1 = float(rng.integer(6, 89)) + corner;
    int major = rng.integer(2, 12), minor = rng.integer(0, major);
    const int steps = rng.integer(1, 3);
    if (rng.chance(0.5f)) std::swap(major, minor);
    const float x2 = x1 + float(major * steps * (rng.chance(0.5f) ? 1 : -1));
    const float y2 = y1 + float(minor * steps * (rng.chance(0.5f) ? 1 : -1));
    add_bresenham_line(scene, rng, width, x1, y1, x2, y2);
  }
  return scene;
}

// Large draws cut into the driver's chunks (docs/lavapipe-rules.md §1.5, cpu_raster/draw_chunks.hpp):
// one clipped triangle makes its chunk "pipelined", and slivers whose float facing (unsnapped
// window coordinates) is back but whose fixed-point facing is front sit just before and after
// each chunk boundary: the pipeline's float cull drops them only inside a pipelined chunk.
// Seeds 1-6 cover lists, strips and fans, indexed and not; the rest are degenerate fillers.
struct ChunkSliver {
  glm::vec2 a, b, c;  // window coordinates; cull back with front_face cw keeps it only unpipelined
};

inline ChunkSliver chunk_sliver(float row, float x0) {
  const float u = 1.0f / 256.0f, y = row + 0.5f;
  return {{x0, y - 0.45f * u}, {x0 + 20, y + 0.45f * u}, {x0 + 60, y + 0.55f * u}};
}

inline Scene chunked_draws(uint32_t seed) {
  const Topology topology =
      std::array{Topology::TriangleList, Topology::TriangleStrip, Topology::TriangleFan}[seed % 3];
  const bool indexed = (seed / 3) % 2 == 1;
  Scene scene = make_scene(scene_name("chunks", seed), 128, 64, format_for(seed));
  Draw draw;
  draw.state = always_state();
  draw.state.cull_mode = CullMode::Back;
  draw.state.front_face = FrontFace::Clockwise;
  draw.topology = topology;
  const uint32_t per_chunk = topology == Topology::TriangleList ? (indexed ? 341 : 1365) : (indexed ? 1022 : 4094);
  const uint32_t count = 2 * per_chunk + per_chunk / 2, clipped_chunk = (seed / 2) % 3;
  const glm::vec2 filler{100.5f, 50.5f}, outside{-5.0f, 5.0f};
  std::vector<glm::vec2> window;  // three per triangle (lists) or the vertex sequence (strips, fans)
  if (topology == Topology::TriangleList) {
    // Slivers at the two boundaries, two primitives either side; the clipped triangle (rows 5-9)
    // and the slivers (rows 12-33) do not meet.
    window.assign(3 * size_t(count), filler);
    const auto put = [&](uint32_t t, glm::vec2 a, glm::vec2 b, glm::vec2 c) {
      window[3 * t] = a, window[3 * t + 1] = b, window[3 * t + 2] = c;
    };
    put(clipped_chunk * per_chunk + 5, outside, {4, 5}, {4, 9});
    for (uint32_t k = 1, slot = 4; k <= 2; ++k)
      for (uint32_t t = k * per_chunk - 2; t <= k * per_chunk + 1; ++t, ++slot) {
        const ChunkSliver s = chunk_sliver(float(3 * slot), 2.0f + float(slot % 3) * 20);
        put(t, s.a, s.b, s.c);
      }
  } else if (topology == Topology::TriangleStrip) {
    // Triangle t (even) is (v_t, v_t+1, v_t+2); a sliver there is framed by copies of a and c so
    // that its neighbours are degenerate. Slivers 6 before and at each boundary.
    window.assign(count + 2, filler);
    for (uint32_t k = 1, slot = 4; k <= 2; ++k)
      for (uint32_t t : {k * per_chunk - 6, k * per_chunk}) {
        const ChunkSliver s = chunk_sliver(float(3 * slot), 2.0f + float(slot % 3) * 20);
        ++slot;
        window[t - 1] = s.a, window[t] = s.a, window[t + 1] = s.b, window[t + 2] = s.c, window[t + 3] = s.c;
      }
    window[clipped_chunk * per_chunk + 10] = outside;  // its triangles are degenerate (two filler corners)
  } else {
    // Fans share vertex 0: one sliver (v0, v_t+1, v_t+2) at the first boundary or just before it.
    // Before it the vertices are the filler; after it they are copies of its last corner c, so
    // the fan's later triangles are degenerate, except the two around the clipped vertex, which
    // lies below the snapped edge a-c and so away from the row samples the sliver covers.
    const ChunkSliver s = chunk_sliver(20, 10);
    const uint32_t t = seed % 2 == 0 ? per_chunk : per_chunk - 1;
    window.assign(count + 2, s.c);
    std::fill(window.begin(), window.begin() + t + 1, filler);
    window[0] = s.a, window[t + 1] = s.b;
    window[clipped_chunk * per_chunk + 10] = glm::vec2{-5.0f, 60.0f};
  }
  for (const glm::vec2& p : window) draw.positions_clip.push_back(clip_from_window(p.x, p.y, 0.5f, scene));
  if (indexed) {
    // Lists: every filler triangle repeats one index (repeats do not change the chunk size).
    const bool list = topology == Topology::TriangleList;
    for (uint32_t k = 0; k < uint32_t(window.size()); ++k)
      draw.indices.push_back(list && window[k] == filler ? 0u : k);  // window[0] is a filler
  }
  scene.draws.push_back(draw);
  return scene;
}

// Strips and fans, indexed or not (primitive order and the provoking-vertex-first vertex order).
inline Scene strips_and_fans(uint32_t seed) {
  Random rng(seed);
  Scene scene = make_scene(scene_name("strips_fans", seed), 83, 71, format_for(seed));
  for (int d = 0; d < 20; ++d) {
    Draw draw;
    draw.state = always_state();
    draw.topology = rng.chance(0.5f) ? Topology::TriangleStrip : Topology::TriangleFan;
    draw.state.cull_mode = rng.pick(std::vector<CullMode>{CullMode::None, CullMode::Back});
    const float cx = rng.uniform(-0.8f, 0.8f), cy = rng.uniform(-0.8f, 0.8f);
    for (int k = 0; k < 12; ++k) {
      const float w = rng.uniform(0.5f, 2);
      draw.positions_clip.push_back(
          {(cx + rng.uniform(-0.5f, 0.5f)) * w, (cy + rng.uniform(-0.5f, 0.5f)) * w, rng.uniform(0, 1) * w, w});
    }
    if (rng.chance(0.5f))
      for (int k = 0; k < 12; ++k) draw.indices.push_back(uint32_t(rng.integer(0, 11)));
    scene.draws.push_back(draw);
  }
  return scene;
}

// 4x multisampling with an inner scissor (coverage and per-sample depth).
inline Scene msaa_triangles(uint32_t seed) {
  Random rng(seed);
  Scene scene = clip_space_triangles("msaa", seed, 1.1f, 0, 1, 0.5f, 2);
  scene.samples = 4;
  if (seed % 2 == 0) {
    const int x0 = seed % 4 == 0 ? 64 : rng.integer(1, 30);  // a scissor edge on a tile boundary too
    scene.scissor = Rect2D{x0, rng.integer(1, 30), uint32_t(rng.integer(8, 50)), uint32_t(rng.integer(8, 40))};
  }
  if (scene.scissor && scene.scissor->x == 64) scene.width = 128;
  return scene;
}

// Overlapping triangles under the LESS compare and a random clear value: the depth test decides
// every overlap.
inline Scene less_triangles(uint32_t seed) {
  Random rng(seed);
  Scene scene = clip_space_triangles("less", seed, 0.7f, 0, 1, 0.5f, 2);
  scene.depth_clear = rng.uniform(0.3f, 1);
  for (Draw& draw : scene.draws) draw.state.depth.compare_op = CompareOp::Less;
  return scene;
}

// 4x multisampling under LESS with interpenetrating triangles: the owner of each sample follows
// from per-sample depth, which is also read back and compared.
inline Scene msaa_less_triangles(uint32_t seed) {
  Random rng(seed);
  Scene scene = clip_space_triangles("msaa_less", seed, 0.6f, 0, 1, 0.5f, 2);
  scene.samples = 4;
  for (Draw& draw : scene.draws) {
    draw.state.depth.compare_op = rng.chance(0.5f) ? CompareOp::Less : CompareOp::GreaterOrEqual;
    if (rng.chance(0.3f)) draw.topology = Topology::LineList, draw.positions_clip.resize(2);
    if (rng.chance(0.3f)) {
      draw.state.depth_bias.enable = true;
      draw.state.depth_bias.constant_factor = rng.uniform(-20, 20);
      draw.state.depth_bias.slope_factor = rng.uniform(-2, 2);
    }
  }
  return scene;
}

// 4x multisampling with depth-tested Bresenham lines between depth-tested triangles (docs/lavapipe-rules.md
// §6): a line fragment is tested against sample 0 and owns all four samples, its depth goes to
// sample 0 only, so the triangles and lines after it see samples 1-3 unchanged.
inline Scene msaa_bresenham_depth(uint32_t seed) {
  Random rng(seed);
  Scene scene = clip_space_triangles("msaa_bresenham_depth", seed, 0.8f, 0, 1, 0.6f, 2);
  scene.samples = 4;
  for (Draw& draw : scene.draws) {
    draw.state.depth.compare_op = rng.pick(
        std::vector<CompareOp>{CompareOp::Less, CompareOp::Less, CompareOp::GreaterOrEqual, CompareOp::NotEqual});
    draw.state.depth.write_enable = rng.chance(0.85f);
    if (rng.chance(0.5f)) {
      draw.topology = Topology::LineList;
      draw.positions_clip.resize(2);
      draw.state.line_mode = LineMode::Bresenham;
      draw.state.line_width = float(rng.integer(1, 4));
    }
  }
  return scene;
}

// Viewports with fractional offsets, partly off-screen, flipped (negative height), with a narrowed
// or inverted depth range; every compare op, a random clear value, some draws without writes.
inline Scene viewport_triangles(uint32_t seed) {
  Random rng(seed);
  Scene scene = clip_space_triangles("viewport", seed, 1.3f, -0.2f, 1.2f, 0.4f, 2.5f);
  Viewport v;
  v.x = rng.uniform(-25, 40);
  v.width = rng.uniform(40, 120);
  const float top = rng.uniform(-25, 30), extent = rng.uniform(40, 100);
  const bool flipped = rng.chance(0.4f);  // negative height: y names the bottom edge
  v.y = flipped ? top + extent : top;
  v.height = flipped ? -extent : extent;
  v.min_depth = rng.uniform(0, 1);
  v.max_depth = rng.uniform(0, 1);
  scene.viewport = v;
  scene.depth_clear = rng.uniform(0, 1);
  const std::vector<CompareOp> ops = {CompareOp::Never,    CompareOp::Less,           CompareOp::Less,
                                      CompareOp::Equal,    CompareOp::LessOrEqual,    CompareOp::Greater,
                                      CompareOp::NotEqual, CompareOp::GreaterOrEqual, CompareOp::Always,
                                      CompareOp::Always,   CompareOp::Always};
  for (Draw& draw : scene.draws) {
    draw.state.depth.compare_op = rng.pick(ops);
    draw.state.depth.write_enable = rng.chance(0.8f);
    draw.state.depth.test_enable = rng.chance(0.9f);
  }
  return scene;
}

}  // namespace rastercmp::differential
