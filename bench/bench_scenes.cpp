#include "bench/bench_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <random>
#include <regex>
#include <string>

#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/profile_support.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "model/camera.hpp"
#include "model/errors.hpp"
#include "model/mesh_import.hpp"
#include "model/scene_io.hpp"

namespace rastercmp::bench {
namespace {

// Uniform in [0, 1) from the 53 high bits: the same numbers on every standard library.
double unit(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

// "80 degrees", "22.5 degrees".
std::string degrees_text(double degrees) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g degrees", degrees);
  return text;
}

// lines_<L>px or lines_<L>px_<A>deg (standard_bench_scene): L and A (or -1: random angles);
// nothing when `name` has neither form.
struct LineShape {
  uint32_t length_px;
  double angle_degrees;
};
std::optional<LineShape> line_shape_of(const std::string& name) {
  static const std::regex form("lines_([0-9]+)px(?:_([0-9]+)deg)?");
  std::smatch m;
  if (!std::regex_match(name, m, form)) return std::nullopt;
  const unsigned long length = m[1].length() > 4 ? 0 : std::stoul(m[1].str());
  if (length < 1 || length > 256)
    throw UsageError("bench scene \"" + name + "\": the line length " + m[1].str() + " px, expected 1-256 px");
  double angle = -1.0;
  if (m[2].matched) {
    const unsigned long degrees = m[2].length() > 4 ? 181 : std::stoul(m[2].str());
    if (degrees > 180)
      throw UsageError("bench scene \"" + name + "\": the angle " + m[2].str() + " degrees, expected 0-180 degrees");
    angle = double(degrees);
  }
  return LineShape{uint32_t(length), angle};
}

void add_quad_indices(std::vector<uint32_t>& indices, uint32_t v00, uint32_t v10, uint32_t v01, uint32_t v11,
                      bool flip) {
  const uint32_t quad[2][6] = {{v00, v10, v11, v00, v11, v01}, {v00, v10, v01, v10, v11, v01}};
  indices.insert(indices.end(), quad[flip], quad[flip] + 6);
}

}  // namespace

Scene fill_layers_scene(bool back_to_front, uint32_t size, uint32_t layers) {
  Scene scene;
  scene.name = back_to_front ? "bench.fill.back_to_front" : "bench.fill.front_to_back";
  scene.description = "overlapping tilted near-full-screen layers";
  scene.width = scene.height = size;
  Draw draw;
  draw.name = "layers";
  constexpr float kExtent = 0.97f;  // about 0.98 Mpx per layer at 1024x1024
  for (uint32_t n = 0; n < layers; ++n) {
    const uint32_t layer = back_to_front ? layers - 1 - n : n;  // layer 0 is the nearest
    const float base = 0.15f + 0.75f * float(layer) / float(std::max(layers - 1, 1u));
    const uint32_t first = uint32_t(draw.positions_clip.size());
    for (int corner = 0; corner < 4; ++corner) {
      const float x = (corner & 1) ? kExtent : -kExtent, y = (corner & 2) ? kExtent : -kExtent;
      draw.positions_clip.emplace_back(x, y, base + 0.01f * x + 0.005f * y, 1.0f);  // the slight tilt
    }
    add_quad_indices(draw.indices, first, first + 1, first + 2, first + 3, false);
  }
  scene.draws.push_back(std::move(draw));
  return scene;
}

Scene grid_scene(uint32_t cells, uint32_t size, uint64_t seed) {
  Scene scene;
  scene.name = "bench.grid." + std::to_string(cells);
  scene.description = "jittered grid of " + std::to_string(2ull * cells * cells) + " triangles";
  scene.width = scene.height = size;
  Draw draw;
  draw.name = "grid";
  std::mt19937_64 rng(seed);
  const double cell = 2.0 / cells;
  draw.positions_clip.reserve(size_t(cells + 1) * (cells + 1));
  for (uint32_t j = 0; j <= cells; ++j) {
    for (uint32_t i = 0; i <= cells; ++i) {
      double x = -1.0 + cell * i, y = -1.0 + cell * j;
      if (i > 0 && i < cells && j > 0 && j < cells) {  // interior: jitter by up to 1/4 cell
        x += (unit(rng) - 0.5) * 0.5 * cell;
        y += (unit(rng) - 0.5) * 0.5 * cell;
      }
      const double z = 0.5 + 0.2 * std::sin(3.0 * x) * std::cos(2.0 * y);
      draw.positions_clip.emplace_back(float(x), float(y), float(z), 1.0f);
    }
  }
  draw.indices.reserve(size_t(cells) * cells * 6);
  for (uint32_t j = 0; j < cells; ++j) {
    for (uint32_t i = 0; i < cells; ++i) {
      const uint32_t v00 = j * (cells + 1) + i;
      add_quad_indices(draw.indices, v00, v00 + 1, v00 + cells + 1, v00 + cells + 2, ((i + j) & 1) != 0);
    }
  }
  scene.draws.push_back(std::move(draw));
  return scene;
}

Scene perspective_scene(uint32_t cells, uint32_t size) {
  Scene scene;
  scene.name = "bench.perspective";
  scene.description = "terrain under a perspective camera, clipped by the view volume";
  scene.width = scene.height = size;
  Camera camera;
  camera.eye = {0.0f, 3.0f, 12.0f};
  camera.target = {0.0f, 0.0f, -10.0f};
  camera.fov_y_degrees = 70.0f;
  camera.near_plane = 1.0f;
  camera.far_plane = 45.0f;
  const glm::mat4 world_to_clip = camera_world_to_clip(camera, 1.0f);
  Draw draw;
  draw.name = "terrain";
  constexpr float kHalf = 60.0f;
  for (uint32_t j = 0; j <= cells; ++j) {
    for (uint32_t i = 0; i <= cells; ++i) {
      const float x = -kHalf + 2 * kHalf * float(i) / float(cells), z = -kHalf + 2 * kHalf * float(j) / float(cells);
      const float y = 1.5f * std::sin(0.35f * x) * std::cos(0.25f * z);
      draw.positions_clip.push_back(world_to_clip * glm::vec4(x, y, z, 1.0f));
    }
  }
  for (uint32_t j = 0; j < cells; ++j) {
    for (uint32_t i = 0; i < cells; ++i) {
      const uint32_t v00 = j * (cells + 1) + i;
      add_quad_indices(draw.indices, v00, v00 + 1, v00 + cells + 1, v00 + cells + 2, false);
    }
  }
  draw.state.cull_mode = CullMode::None;
  scene.draws.push_back(std::move(draw));
  return scene;
}

Scene lines_scene(uint32_t count, uint32_t size, uint64_t seed) {
  Scene scene;
  scene.name = "bench.lines." + std::to_string(count);
  scene.description = std::to_string(count) + " random line segments of up to 1/8 of the width, D32, LESS";
  scene.width = scene.height = size;
  Draw draw;
  draw.name = "lines";
  draw.topology = Topology::LineList;
  std::mt19937_64 rng(seed);
  for (uint32_t n = 0; n < count; ++n) {
    const double x = 2.0 * unit(rng) - 1.0, y = 2.0 * unit(rng) - 1.0, z = 0.1 + 0.8 * unit(rng);
    const double angle = 6.283185307179586 * unit(rng), length = 0.25 * unit(rng);
    draw.positions_clip.emplace_back(float(x), float(y), float(z), 1.0f);
    draw.positions_clip.emplace_back(float(x + length * std::cos(angle)), float(y + length * std::sin(angle)),
                                     float(z + 0.1 * (unit(rng) - 0.5)), 1.0f);
  }
  scene.draws.push_back(std::move(draw));
  return scene;
}

Scene line_shape_scene(uint32_t count, uint32_t length_px, double angle_degrees, uint32_t size, uint64_t seed) {
  Scene scene;
  const std::string angle = angle_degrees < 0 ? std::string("random angles") : degrees_text(angle_degrees);
  scene.name = "bench.lines." + std::to_string(length_px) + "px, " + angle;
  scene.description = std::to_string(count) + " line segments of " + std::to_string(length_px) + " px, " + angle +
                      ", wholly inside the frame, D32, LESS";
  scene.width = scene.height = size;
  Draw draw;
  draw.name = "lines";
  draw.topology = Topology::LineList;
  std::mt19937_64 rng(seed);
  const double half = 0.5 * double(length_px), pixel = 2.0 / double(size);  // clip units per pixel
  for (uint32_t n = 0; n < count; ++n) {
    const double turn = unit(rng) < 0.5 ? 0.0 : 180.0;  // either way along the angle
    const double radians =
        (angle_degrees < 0 ? 360.0 * unit(rng) : angle_degrees + turn) * 3.141592653589793 / 180.0;
    const double dx = half * std::cos(radians), dy = half * std::sin(radians);  // pixels from the centre
    // the centre at least |dx| + 1, |dy| + 1 px from every side
    const double cx = std::abs(dx) + 1.0 + (double(size) - 2.0 * std::abs(dx) - 2.0) * unit(rng);
    const double cy = std::abs(dy) + 1.0 + (double(size) - 2.0 * std::abs(dy) - 2.0) * unit(rng);
    const double z = 0.1 + 0.8 * unit(rng);
    draw.positions_clip.emplace_back(float((cx - dx) * pixel - 1.0), float((cy - dy) * pixel - 1.0), float(z), 1.0f);
    draw.positions_clip.emplace_back(float((cx + dx) * pixel - 1.0), float((cy + dy) * pixel - 1.0),
                                     float(z + 0.1 * (unit(rng) - 0.5)), 1.0f);
  }
  scene.draws.push_back(std::move(draw));
  return scene;
}

Scene msaa_grid_scene(uint32_t cells, uint32_t size) {
  Scene scene = grid_scene(cells, size);
  scene.name = "bench.msaa4.grid." + std::to_string(cells);
  scene.description = "jittered grid of " + std::to_string(2ull * cells * cells) + " triangles, 4 samples per pixel";
  scene.samples = 4;
  return scene;
}

Scene engine_scene(uint32_t width, uint32_t height) {
  ImportOptions options;
  options.name = "bench.engine";
  options.width = width;
  options.height = height;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(kEngineModel, ec))
    throw InputError(kEngineModel, "", "expected the model of Debian's assimp-testmodels (scripts/setup.sh installs it)");
  return parse_scene(import_model_json(kEngineModel, options), kEngineModel);
}

std::vector<std::string> standard_bench_scene_names() {
  return {"fill_b2f", "fill_f2b", "grid_180k", "tiny_1m", "perspective", "lines_20k", "msaa4_grid", "engine_1080p"};
}

BenchScene standard_bench_scene(const std::string& name) {
  if (name == "fill_b2f") return {name, fill_layers_scene(true)};
  if (name == "fill_f2b") return {name, fill_layers_scene(false)};
  if (name == "grid_180k") return {name, grid_scene(300)};
  if (name == "tiny_1m") return {name, grid_scene(724)};
  if (name == "perspective") return {name, perspective_scene()};
  if (name == "lines_20k") return {name, lines_scene(20000)};
  if (name == "msaa4_grid") return {name, msaa_grid_scene(100, 512)};
  if (name == "engine_1080p") return {name, engine_scene()};
  if (const std::optional<LineShape> shape = line_shape_of(name))
    return {name, line_shape_scene(20000, shape->length_px, shape->angle_degrees)};
  throw UsageError("unknown bench scene \"" + name +
                   "\"; known: fill_b2f, fill_f2b, grid_180k, tiny_1m, perspective, lines_20k, msaa4_grid, engine_1080p, "
                   "lines_<L>px, lines_<L>px_<A>deg");
}

std::vector<BenchScene> standard_bench_scenes() {
  std::vector<BenchScene> scenes;
  for (const std::string& name : standard_bench_scene_names()) scenes.push_back(standard_bench_scene(name));
  return scenes;
}

std::vector<Scene> load_scene_suite(const std::string& root) {
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec))
    throw InputError(root, "", "expected a suite folder with scene files (*.json)");
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root, ec))
    if (entry.is_regular_file() && entry.path().extension() == ".json") paths.push_back(entry.path().string());
  if (ec) throw InputError(root, "", "expected a readable folder: " + ec.message());
  std::sort(paths.begin(), paths.end());
  std::vector<Scene> scenes;
  for (const std::string& path : paths) scenes.push_back(load_scene_file(path));  // the suite row: scene files only
  return scenes;
}

uint64_t triangle_count(const Scene& scene) {
  uint64_t count = 0;
  for (const Draw& draw : scene.draws) {
    const uint64_t n = draw.vertex_count();
    if (draw.topology == Topology::TriangleList)
      count += n / 3;
    else if (is_triangle_topology(draw.topology))
      count += n >= 3 ? n - 2 : 0;
  }
  return count;
}

uint64_t covered_samples(const Scene& scene, bool fma) {
  cpu::check_lavapipe_profile_support(scene);
  const cpu::FrameContext frame = cpu::make_frame_context(scene, fma, cpu::SetupMethods{});
  uint64_t count = 0;
  for (uint32_t d = 0; d < scene.draws.size(); ++d) {
    cpu::run_front_end(frame, d, [&](const cpu::PrimitiveOutcome& outcome) {
      if (!outcome.rasterized()) return;
      const cpu::RasterPrimitive& p = outcome.raster;
      for (int32_t py = p.visit.y0; py <= p.visit.y1; ++py)
        for (int32_t px = p.visit.x0; px <= p.visit.x1; ++px)
          for (uint32_t s = 0; s < scene.samples; ++s) {
            const cpu::SamplePoint point = cpu::sample_point(px, py, p.per_sample ? s : 0, p.per_sample);
            if (cpu::first_failing_plane(p.planes, point.x_fixed, point.y_fixed) < 0) ++count;
          }
    });
  }
  return count;
}

}  // namespace rastercmp::bench
