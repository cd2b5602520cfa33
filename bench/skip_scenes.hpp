// Scenes in which one of the exact path's work skips (cpu_raster/work_skips.hpp) matters: jittered
// grid meshes, one indexed draw each. The benchmark (bench/bench_skips.cpp) renders large ones; the
// test (tests/test_work_skips.cpp) renders small ones on both the CPU and lavapipe.
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "model/scene.hpp"

namespace rastercmp::skip_scenes {

struct MeshSpec {
  uint32_t size = 256;  // framebuffer side, pixels
  uint32_t cells = 32;  // grid cells per side: 2 * cells^2 triangles of about (size/cells)^2 / 2 px
  float reach = 0.95f;  // |x|, |y| <= reach * w: < 1 keeps every vertex inside, > 1 crosses the planes
  DepthFormat format = DepthFormat::X8D24Unorm;
  bool bias = false;  // depth bias on (constant 2, slope 1.5)
  uint32_t seed = 1;
};

// A (cells+1)^2-vertex grid over [-reach, reach]^2 in NDC, interior vertices jittered by up to 0.3 of
// a cell, z in [0.2, 0.8] and w in [1, 2] per vertex (positions scaled by w), depth LESS with writes.
inline Scene grid_mesh(const std::string& name, const MeshSpec& spec) {
  std::mt19937 rng(spec.seed);
  const auto unit = [&rng] { return float(rng() >> 8) * (1.0f / 16777216.0f); };  // [0, 1), same on every host
  Scene scene;
  scene.name = name;
  scene.width = scene.height = spec.size;
  scene.depth_format = spec.format;
  Draw draw;
  draw.name = name;
  const float step = 2.0f * spec.reach / float(spec.cells);
  for (uint32_t j = 0; j <= spec.cells; ++j) {
    for (uint32_t i = 0; i <= spec.cells; ++i) {
      const bool interior = i > 0 && j > 0 && i < spec.cells && j < spec.cells;
      const float jx = interior ? (unit() - 0.5f) * 0.6f * step : 0.0f;
      const float jy = interior ? (unit() - 0.5f) * 0.6f * step : 0.0f;
      const float x = -spec.reach + float(i) * step + jx, y = -spec.reach + float(j) * step + jy;
      const float z = 0.2f + 0.6f * unit(), w = 1.0f + unit();
      draw.positions_clip.push_back({x * w, y * w, z * w, w});
    }
  }
  const uint32_t row = spec.cells + 1;
  for (uint32_t j = 0; j < spec.cells; ++j) {
    for (uint32_t i = 0; i < spec.cells; ++i) {
      const uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
      if ((i + j) % 2 == 0)
        draw.indices.insert(draw.indices.end(), {a, b, d, a, d, c});
      else
        draw.indices.insert(draw.indices.end(), {a, b, c, b, d, c});
    }
  }
  draw.state.depth.compare_op = CompareOp::Less;
  if (spec.bias) draw.state.depth_bias = DepthBias{true, 2.0f, 1.5f, 0.0f};
  scene.draws.push_back(std::move(draw));
  return scene;
}

}  // namespace rastercmp::skip_scenes
