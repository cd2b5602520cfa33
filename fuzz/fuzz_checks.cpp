#include "fuzz/fuzz_checks.hpp"

#include <array>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/clip_triangle.hpp"
#include "cpu_raster/exact/clip_vertex.hpp"
#include "cpu_raster/exact/viewport.hpp"
#include "model/errors.hpp"
#include "model/scene_io.hpp"

namespace rastercmp::fuzz {
namespace {

bool small_enough_to_render(const Scene& scene) {
  if (uint64_t(scene.width) * scene.height * scene.samples > 128 * 128) return false;
  uint64_t vertices = 0;
  for (const Draw& draw : scene.draws) vertices += draw.vertex_count();
  return vertices <= 512;
}

}  // namespace

void check_scene_parser(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Scene scene;
  try {
    scene = parse_scene(text, "fuzz.json");
  } catch (const InputError&) {
    return;
  }
  if (!small_enough_to_render(scene)) return;
  try {
    (void)render_cpu(scene, CpuOptions{});
  } catch (const NotSupportedError&) {
  }
}

void check_clipper(const uint8_t* data, size_t size) {
  constexpr size_t kFloats = 12;
  if (size < kFloats * sizeof(float) + 2) return;
  float values[kFloats];
  std::memcpy(values, data, sizeof(values));
  const bool depth_clip = data[kFloats * sizeof(float)] & 1;
  const bool fma = data[kFloats * sizeof(float) + 1] & 1;

  const cpu::ViewportTransform viewport = cpu::make_viewport_transform(Viewport{0, 0, 64, 48, 0, 1});
  std::array<cpu::ClipVertex, 3> triangle;
  for (int v = 0; v < 3; ++v) {
    const glm::vec4 pos_clip(values[v * 4], values[v * 4 + 1], values[v * 4 + 2], values[v * 4 + 3]);
    triangle[v] = cpu::make_clip_vertex(pos_clip, viewport, depth_clip, fma);
  }
  const cpu::ClippedTriangles clipped = cpu::clip_triangle(triangle, viewport);
  constexpr size_t kMaxFan = (3 + 6) - 2;  // a triangle cut by all six planes
  if (clipped.triangles.size() > kMaxFan) std::abort();
  if (clipped.fate == cpu::ClipFate::Inside) {
    if (clipped.triangles.size() != 1) std::abort();
    for (int v = 0; v < 3; ++v)
      if (std::memcmp(&clipped.triangles[0][v].pos_clip, &triangle[v].pos_clip, sizeof(glm::vec4)) != 0) std::abort();
  }
  if (clipped.fate == cpu::ClipFate::Outside && !clipped.triangles.empty()) std::abort();
}

}  // namespace rastercmp::fuzz
