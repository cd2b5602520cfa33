// `rastercmp chart depth-precision`: the depth resolution Δz(w) of each depth format under each
// depth mapping, measured through the exact path's own arithmetic and set beside the analytic curve.
//
// A surface facing the eye at eye distance w (clip w = w) stores one raw value. The set of float
// eye distances that store the same raw value is a bucket; its width is the smallest eye-distance
// step sure to change the stored depth, Δz(w). It is found by bisection over the float bit patterns
// of w on the stored raw value, each evaluation taking the exact path's steps:
//   clip z       the mapping, in the same float or double operations the scenes use (below)
//   window z     window_from_clip_jit (cpu_raster/exact/viewport.hpp), viewport depth 0..1
//   stored raw   sample_depth on the flat plane a0 = window z (clamp to 0..1, depth_to_raw)
// and a render check renders the bucket's edges and their outer neighbours with render_cpu (a 4x4
// quad at the same clip positions) and requires the same raw values.
//
// Mappings (near n, far f; clip z with clip w = w):
//   standard           camera_world_to_clip (model/camera.hpp): fl(fl(f/(n-f) * -w) + -(f n)/(f-n)),
//                      the matrix a scene's camera makes; LESS, clear 1
//   reversed           reversed_z (experiments/method_map_scenes.hpp): n (f - w) / (f - n) in double,
//                      rounded once to float; GREATER, clear 0
//   standard_infinite  the matrix of glm::infinitePerspective (0..1 depth): fl(-1 * -w + -n) = fl(w - n)
//   reversed_infinite  a matrix whose z row gives n: clip z = n, window z = fl(n * fl(1/w))
//
// The analytic step: window z(w) has slope |dz/dw| = f n / ((f - n) w^2) for both finite mappings and
// n / w^2 for both infinite ones; a format resolves q(z) in z (UNORM: 1 / (2^B - 1); D32: the float
// spacing at z, 2^(floor(log2 z) - 23)), so Δz ~ q(z) / |dz/dw|:
//   finite    Δz = q(z) w^2 (f - n) / (f n)        (UNORM standard: w^2 (f - n) / (f n (2^B - 1)))
//   infinite  Δz = q(z) w^2 / n
// The ideal bucket is the same in exact arithmetic: the z interval that rounds to the raw value
// nearest the exact z(w), mapped back through w(z) (no first-order approximation).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "experiments/sweep_common.hpp"
#include "model/scene.hpp"

namespace rastercmp::experiments {

enum class PrecisionMapping { Standard, Reversed, StandardInfinite, ReversedInfinite };
inline constexpr PrecisionMapping kPrecisionMappings[] = {PrecisionMapping::Standard, PrecisionMapping::Reversed,
                                                  PrecisionMapping::StandardInfinite, PrecisionMapping::ReversedInfinite};
const char* to_string(PrecisionMapping mapping);
bool is_reversed(PrecisionMapping mapping);

struct DepthPlanes {
  double near_plane = 0.1, far_plane = 1000;
};

// The clip position of the surface's vertices at eye distance w (x, y = ±0.9 w; z by the mapping).
float mapped_clip_z(PrecisionMapping mapping, float w, const DepthPlanes& planes);

// What the exact path stores for that surface (the stage functions, no render).
uint32_t stored_depth_raw(DepthFormat format, PrecisionMapping mapping, float w, const DepthPlanes& planes);

// The same value from a render_cpu render of a 4x4 frame covered by the surface (pixel 1,1).
uint32_t rendered_depth_raw(DepthFormat format, PrecisionMapping mapping, float w, const DepthPlanes& planes);

// The float eye distances around w0 that store w0's raw value: [w_low, w_high], both stored values;
// `open` when the bucket reaches the search range's end (a clamped z: below near, beyond far).
struct DepthBucket {
  float w_low = 0, w_high = 0;
  uint32_t raw = 0;
  bool open = false;
  double width() const;  // from w_low to the float after w_high
};
DepthBucket depth_bucket(DepthFormat format, PrecisionMapping mapping, float w0, const DepthPlanes& planes);

// The window z of the mapping at w in exact arithmetic, and its inverse.
double exact_window_z(PrecisionMapping mapping, double w, const DepthPlanes& planes);
double eye_distance_at(PrecisionMapping mapping, double z, const DepthPlanes& planes);

double analytic_step(DepthFormat format, PrecisionMapping mapping, double w, const DepthPlanes& planes);
double ideal_bucket_width(DepthFormat format, PrecisionMapping mapping, double w, const DepthPlanes& planes);
double float_spacing(float w);  // the float after w minus w

struct PrecisionPoint {
  DepthFormat format = DepthFormat::D16Unorm;
  PrecisionMapping mapping = PrecisionMapping::Standard;
  float w = 0;
  DepthBucket bucket;
  double measured = 0, analytic = 0, ideal = 0, w_spacing = 0;
  bool render_agrees = false;  // render_cpu stores the bucket's edges and their neighbours alike
};

// w = n (f/n)^(k/K) for k = 0..K, K = decades * per_decade, rounded to float.
std::vector<float> eye_distances(const DepthPlanes& planes, int per_decade);

// Every format (sweep_depth_formats) x mapping x eye distance; `render_check` runs the render check.
std::vector<PrecisionPoint> measure_depth_precision(const DepthPlanes& planes, int per_decade, bool render_check);

// The command: CSV, JSON, charts, index.html in options.out_dir (10 points per decade, 4 with --quick).
void run_depth_precision(const SweepOptions& options, const DepthPlanes& planes);

}  // namespace rastercmp::experiments
