// The benchmark scenes of docs/performance.md, built in code (shared by `rastercmp bench`, the
// Google Benchmark binary in bench/ and the fast path's tests, which use smaller sizes):
//  - fill: 16 overlapping near-full-screen layers (a tilted quad of 2 triangles each), D32,
//    LESS, writes on, drawn back to front (every layer passes) or front to back;
//  - grid: cells x cells quads of 2 triangles over the whole framebuffer, interior vertices
//    jittered by up to 1/4 cell, z = 0.5 + 0.2 sin(3x) cos(2y): 300 cells give 180,000 triangles
//    of about 5.8 px at 1024x1024, 724 cells 1,048,352 triangles of about 1 px;
//  - perspective: a rolling terrain seen by a perspective camera, cut by the near, far and side
//    planes of the view volume;
//  - lines: random line segments (1 px wide, up to 1/8 of the width long), D32, LESS; and by
//    name lines of one length, at one angle or at random ones (line_shape_scene);
//  - msaa4_grid: a grid (as above) rendered with 4 samples per pixel;
//  - engine_1080p: a real model, the Khronos 2CylinderEngine (glTF binary, 115 meshes, 121,496
//    triangles) from Debian's assimp-testmodels, imported with the framing camera at 1920x1080.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/scene.hpp"

namespace rastercmp::bench {

Scene fill_layers_scene(bool back_to_front, uint32_t size = 1024, uint32_t layers = 16);
Scene grid_scene(uint32_t cells, uint32_t size = 1024, uint64_t seed = 1);
Scene perspective_scene(uint32_t cells = 200, uint32_t size = 1024);
Scene lines_scene(uint32_t count, uint32_t size = 1024, uint64_t seed = 1);
// `count` lines of length_px pixels each, at angle_degrees from the x axis (either way along it) or,
// below 0, at random angles, every one wholly inside a size x size frame at a random place and
// depth (D32, LESS): what a line costs by its length and by its rows (docs/performance-log.md).
Scene line_shape_scene(uint32_t count, uint32_t length_px, double angle_degrees, uint32_t size = 512,
                       uint64_t seed = 7);
Scene msaa_grid_scene(uint32_t cells, uint32_t size = 512);
// The 2CylinderEngine model (kEngineModel) imported at width x height; InputError naming the file
// when assimp-testmodels is not installed.
Scene engine_scene(uint32_t width = 1920, uint32_t height = 1080);
inline constexpr const char* kEngineModel =
    "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

struct BenchScene {
  std::string name;  // short id for tables and --scene
  Scene scene;
};

// fill_b2f, fill_f2b, grid_180k, tiny_1m, perspective, lines_20k, msaa4_grid, engine_1080p
// (docs/performance.md). By name also lines_<L>px and lines_<L>px_<A>deg (not among these):
// line_shape_scene(20000, L, A or random angles) in a 512 px frame, L 1-256, A 0-180.
std::vector<BenchScene> standard_bench_scenes();
std::vector<std::string> standard_bench_scene_names();
// One of the standard scenes by name; throws UsageError naming the known ones.
BenchScene standard_bench_scene(const std::string& name);

// Every scenes/**/*.json under `root`, sorted by path (loader errors propagate; a missing or
// unreadable folder is an InputError).
std::vector<Scene> load_scene_suite(const std::string& root);

// Triangles the scene's draws form (its primitives, for Mtri/s).
uint64_t triangle_count(const Scene& scene);

// Samples covered by some primitive, summed over primitives (fragments before the depth test,
// for Mpix/s), from the exact path's front end and coverage test.
uint64_t covered_samples(const Scene& scene, bool fma);

}  // namespace rastercmp::bench
