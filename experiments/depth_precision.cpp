#include "experiments/depth_precision.hpp"

#include <bit>
#include <cmath>
#include <limits>

#include <glm/mat4x4.hpp>

#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/viewport.hpp"
#include "experiments/method_map_scenes.hpp"
#include "model/camera.hpp"
#include "model/depth_format.hpp"
#include "model/render_result.hpp"

namespace rastercmp::experiments {
namespace {

// The camera every mapping shares: at the origin, looking down -z (view = identity).
Camera eye_camera(const DepthPlanes& planes) {
  Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.up = {0, 1, 0};
  camera.fov_y_degrees = 45;
  camera.near_plane = float(planes.near_plane);
  camera.far_plane = float(planes.far_plane);
  return camera;
}

// The projection of `camera` with its z row replaced: clip z = m22 * z_eye + m32 (clip w = -z_eye).
glm::mat4 with_z_row(glm::mat4 m, float m22, float m32) {
  m[2][2] = m22;
  m[3][2] = m32;
  return m;
}

// A 4x4 frame covered by a quad of two triangles at clip positions (±0.9 w, ±0.9 w, z, w).
Scene surface_scene(DepthFormat format, float z, float w) {
  Scene scene;
  scene.name = "experiments.depth_precision";
  scene.width = scene.height = 4;
  scene.depth_format = format;
  Draw draw;
  const float x = 0.9f * w;
  draw.positions_clip = {{-x, -x, z, w}, {x, -x, z, w}, {x, x, z, w}, {-x, -x, z, w}, {x, x, z, w}, {-x, x, z, w}};
  scene.draws.push_back(draw);
  return scene;
}

// Order of raw values as depth order (D32: +0 and -0 alike).
int64_t order(DepthFormat format, uint32_t raw) { return depth_raw_order(format, raw); }

float float_from_bits(uint32_t bits) { return std::bit_cast<float>(bits); }
uint32_t bits_of(float v) { return std::bit_cast<uint32_t>(v); }

}  // namespace

const char* to_string(PrecisionMapping mapping) {
  switch (mapping) {
    case PrecisionMapping::Standard: return "standard";
    case PrecisionMapping::Reversed: return "reversed";
    case PrecisionMapping::StandardInfinite: return "standard_infinite";
    case PrecisionMapping::ReversedInfinite: return "reversed_infinite";
  }
  return "?";
}

bool is_reversed(PrecisionMapping mapping) {
  return mapping == PrecisionMapping::Reversed || mapping == PrecisionMapping::ReversedInfinite;
}

float mapped_clip_z(PrecisionMapping mapping, float w, const DepthPlanes& planes) {
  const glm::vec4 eye_point(0.0f, 0.0f, -w, 1.0f);
  const glm::mat4 camera = camera_world_to_clip(eye_camera(planes), 1.0f);
  switch (mapping) {
    case PrecisionMapping::Standard: return (camera * eye_point).z;  // as a scene's world positions
    case PrecisionMapping::Reversed: {
      Scene scene = surface_scene(DepthFormat::D32Sfloat, (camera * eye_point).z, w);
      return reversed_z(std::move(scene), planes.near_plane, planes.far_plane).draws[0].positions_clip[0].z;
    }
    case PrecisionMapping::StandardInfinite:  // glm::infinitePerspectiveRH_ZO: z row (-1, -near)
      return (with_z_row(camera, -1.0f, -float(planes.near_plane)) * eye_point).z;
    case PrecisionMapping::ReversedInfinite:  // z row (0, near): z_ndc = near / w
      return (with_z_row(camera, 0.0f, float(planes.near_plane)) * eye_point).z;
  }
  return 0;
}

uint32_t stored_depth_raw(DepthFormat format, PrecisionMapping mapping, float w, const DepthPlanes& planes) {
  const cpu::ViewportTransform viewport = cpu::make_viewport_transform(Viewport{0, 0, 4, 4, 0, 1});
  const glm::vec4 clip(0.0f, 0.0f, mapped_clip_z(mapping, w, planes), w);
  // Scale 1, translate 0: fused or not, window z = fl(z_clip * fl(1/w)).
  const float window_z = cpu::window_from_clip_jit(clip, viewport, true).z;
  // Every vertex has this z, so the plane is a0 = window z with zero slopes (depth_plane.cpp).
  const cpu::DepthPlane plane{window_z, 0.0f, 0.0f};
  return cpu::sample_depth(plane, 0.0f, 1.5f, 1.5f, cpu::DepthRange{}, format, true).raw;
}

uint32_t rendered_depth_raw(DepthFormat format, PrecisionMapping mapping, float w, const DepthPlanes& planes) {
  Scene scene = surface_scene(format, mapped_clip_z(mapping, w, planes), w);
  if (is_reversed(mapping)) {  // compare op and clear of reversed Z; clip z as above
    scene.depth_clear = 0.0f;
    scene.draws[0].state.depth.compare_op = CompareOp::Greater;
  }
  const RenderResult result = render_cpu(scene, exact_cpu_options());
  return result.depth_raw[result.index(1, 1)];
}

double DepthBucket::width() const {
  return double(std::nextafter(w_high, std::numeric_limits<float>::infinity())) - double(w_low);
}

DepthBucket depth_bucket(DepthFormat format, PrecisionMapping mapping, float w0, const DepthPlanes& planes) {
  // The search range: far enough beyond the planes that z is clamped at both ends (finite mappings).
  const uint32_t floor_bits = bits_of(float(planes.near_plane / 1024)), ceiling_bits = bits_of(float(planes.far_plane * 1024));
  DepthBucket bucket;
  bucket.raw = stored_depth_raw(format, mapping, w0, planes);
  const int64_t key = order(format, bucket.raw);
  const int direction = is_reversed(mapping) ? -1 : 1;  // how stored order moves as w grows
  // Positive floats are ordered as their bits: bisect on the bits. `same_side(b, up)`: the value at
  // b has not passed the bucket's key in the direction of search.
  const auto passed = [&](uint32_t bits, bool up) {
    const int64_t k = order(format, stored_depth_raw(format, mapping, float_from_bits(bits), planes));
    return up ? (direction > 0 ? k > key : k < key) : (direction > 0 ? k < key : k > key);
  };
  const uint32_t b0 = bits_of(w0);
  // Upper edge: the largest bits in [b0, ceiling] that have not passed.
  uint32_t lo = b0, hi = ceiling_bits;
  if (!passed(hi, true)) {
    bucket.open = true;
    lo = hi;
  }
  while (hi - lo > 1) {
    const uint32_t mid = lo + (hi - lo) / 2;
    (passed(mid, true) ? hi : lo) = mid;
  }
  bucket.w_high = float_from_bits(lo);
  // Lower edge: the smallest bits in [floor, b0] that have not passed.
  lo = floor_bits;
  hi = b0;
  if (!passed(lo, false)) {
    bucket.open = true;
    hi = lo;
  }
  while (hi - lo > 1) {
    const uint32_t mid = lo + (hi - lo) / 2;
    (passed(mid, false) ? lo : hi) = mid;
  }
  bucket.w_low = float_from_bits(hi);
  return bucket;
}

double exact_window_z(PrecisionMapping mapping, double w, const DepthPlanes& planes) {
  const double n = planes.near_plane, f = planes.far_plane;
  switch (mapping) {
    case PrecisionMapping::Standard: return f * (w - n) / (w * (f - n));
    case PrecisionMapping::Reversed: return n * (f - w) / (w * (f - n));
    case PrecisionMapping::StandardInfinite: return 1 - n / w;
    case PrecisionMapping::ReversedInfinite: return n / w;
  }
  return 0;
}

double eye_distance_at(PrecisionMapping mapping, double z, const DepthPlanes& planes) {
  const double n = planes.near_plane, f = planes.far_plane;
  switch (mapping) {
    case PrecisionMapping::Standard: return f * n / (f - z * (f - n));
    case PrecisionMapping::Reversed: return n * f / (n + z * (f - n));
    case PrecisionMapping::StandardInfinite: return n / (1 - z);
    case PrecisionMapping::ReversedInfinite: return n / z;
  }
  return 0;
}

namespace {

// The format's resolution in window z at z: UNORM 1/(2^B - 1); float: the spacing of floats at z.
double z_quantum(DepthFormat format, double z) {
  const DepthFormatInfo info = depth_format_info(format);
  if (info.encoding == DepthEncoding::Unorm) return info.mrd;
  return std::ldexp(1.0, std::ilogb(z) - int(info.mantissa_bits));
}

}  // namespace

double analytic_step(DepthFormat format, PrecisionMapping mapping, double w, const DepthPlanes& planes) {
  const double n = planes.near_plane, f = planes.far_plane;
  const double q = z_quantum(format, exact_window_z(mapping, w, planes));
  const bool infinite = mapping == PrecisionMapping::StandardInfinite || mapping == PrecisionMapping::ReversedInfinite;
  return infinite ? q * w * w / n : q * w * w * (f - n) / (f * n);
}

double ideal_bucket_width(DepthFormat format, PrecisionMapping mapping, double w, const DepthPlanes& planes) {
  const double z = exact_window_z(mapping, w, planes);
  const DepthFormatInfo info = depth_format_info(format);
  double z_low = 0, z_high = 0;
  if (info.encoding == DepthEncoding::Unorm) {  // round to nearest of z (2^B - 1)
    const double steps = double(unorm_max(info)), k = std::nearbyint(z * steps);
    z_low = (k - 0.5) / steps;
    z_high = (k + 0.5) / steps;
  } else {  // round to the nearest float: half way to each neighbour
    const float zk = float(z);
    z_low = (double(zk) + double(std::nextafter(zk, 0.0f))) / 2;
    z_high = (double(zk) + double(std::nextafter(zk, 2.0f))) / 2;
  }
  return std::fabs(eye_distance_at(mapping, z_high, planes) - eye_distance_at(mapping, z_low, planes));
}

double float_spacing(float w) {
  return double(std::nextafter(w, std::numeric_limits<float>::infinity())) - double(w);
}

std::vector<float> eye_distances(const DepthPlanes& planes, int per_decade) {
  const double decades = std::log10(planes.far_plane / planes.near_plane);
  const int steps = std::max(1, int(std::ceil(decades * per_decade - 1e-9)));
  std::vector<float> out;
  for (int k = 0; k <= steps; ++k)
    out.push_back(float(planes.near_plane * std::pow(planes.far_plane / planes.near_plane, double(k) / steps)));
  return out;
}

std::vector<PrecisionPoint> measure_depth_precision(const DepthPlanes& planes, int per_decade, bool render_check) {
  std::vector<PrecisionPoint> points;
  const float inf = std::numeric_limits<float>::infinity();
  for (DepthFormat format : sweep_depth_formats())
    for (PrecisionMapping mapping : kPrecisionMappings)
      for (float w : eye_distances(planes, per_decade)) {
        PrecisionPoint p;
        p.format = format;
        p.mapping = mapping;
        p.w = w;
        p.bucket = depth_bucket(format, mapping, w, planes);
        p.measured = p.bucket.width();
        p.analytic = analytic_step(format, mapping, w, planes);
        p.ideal = ideal_bucket_width(format, mapping, w, planes);
        p.w_spacing = float_spacing(w);
        if (render_check) {
          // The edges store the bucket's value, their outer neighbours another. An open bucket reaches
          // beyond a clip plane, where the renderer draws nothing: there w itself is checked.
          const auto rendered = [&](float v) { return rendered_depth_raw(format, mapping, v, planes); };
          p.render_agrees = p.bucket.open ? rendered(w) == p.bucket.raw
                                          : rendered(p.bucket.w_low) == p.bucket.raw &&
                                                rendered(p.bucket.w_high) == p.bucket.raw &&
                                                rendered(std::nextafter(p.bucket.w_low, 0.0f)) != p.bucket.raw &&
                                                rendered(std::nextafter(p.bucket.w_high, inf)) != p.bucket.raw;
        }
        points.push_back(p);
      }
  return points;
}

}  // namespace rastercmp::experiments
