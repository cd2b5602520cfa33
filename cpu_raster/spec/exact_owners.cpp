#include "cpu_raster/spec/exact_owners.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/raster_primitive.hpp"
#include "cpu_raster/spec/coverage_map.hpp"
#include "cpu_raster/spec/depth_gate.hpp"
#include "cpu_raster/spec/subpixel.hpp"
#include "model/depth_format.hpp"

namespace rastercmp::cpu::spec {
namespace {

// The simulation's grid: the device's 2^-bits grid, refined to 2^-3 at least so that the
// standard 4x sample positions (eighths of a pixel) lie on it.
uint32_t grid_bits(uint32_t sub_pixel_bits) { return std::max<uint32_t>(sub_pixel_bits, 3); }

int64_t snap(double window, uint32_t bits, SnapRounding rounding) {
  const double scaled = window * std::ldexp(1.0, int(bits));  // exact: a power of two
  switch (rounding) {
    case SnapRounding::Nearest: return int64_t(std::nearbyint(scaled));  // ties to even
    case SnapRounding::Floor: return int64_t(std::floor(scaled));
    case SnapRounding::Ceil: return int64_t(std::ceil(scaled));
  }
  return 0;
}

// Where a device's depth bias sits in SnappedPlane::bias: r and m are chosen apart ("Depth Bias
// Computation" bounds r and lets m be approximated, independently).
size_t bias_index(bool r_high, bool m_sqrt) { return (r_high ? 2 : 0) + (m_sqrt ? 1 : 0); }

// One triangle on one device's grid, oriented so that its edge functions are positive inside.
struct SnappedPlane {
  bool drawn = false;  // not culled, not of zero area
  std::array<int64_t, 3> x{}, y{};
  std::array<long double, 3> z{};
  Wide area = 0;  // cross(v1 - v0, v2 - v0) > 0, grid units squared
  std::array<bool, 3> top_left{};
  std::array<double, 4> bias{};  // o for bias_index(device) (0 without bias)
};

SnappedPlane snapped_plane(const Scene& scene, const SpecTriangle& t, uint32_t bits, SnapRounding rounding) {
  SnappedPlane p;
  const uint32_t gbits = grid_bits(bits);
  const int64_t refine = int64_t(1) << (gbits - bits);
  for (size_t k = 0; k < 3; ++k) {
    p.x[k] = snap(t.window[k].x, bits, rounding) * refine;
    p.y[k] = snap(t.window[k].y, bits, rounding) * refine;
    p.z[k] = t.window[k].z;
  }
  // y points down: cross > 0 is clockwise on screen, Vulkan's a = -cross / 2 < 0.
  Wide cross = Wide(p.x[1] - p.x[0]) * (p.y[2] - p.y[0]) - Wide(p.x[2] - p.x[0]) * (p.y[1] - p.y[0]);
  if (cross == 0) return p;  // zero area: no sample lies inside
  const Draw& draw = scene.draws[t.draw_index];
  if (facing_gate(draw.state, cross > 0 ? -1 : 1) == Gate::Never) return p;
  if (cross < 0) {
    std::swap(p.x[1], p.x[2]);
    std::swap(p.y[1], p.y[2]);
    std::swap(p.z[1], p.z[2]);
    cross = -cross;
  }
  p.area = cross;
  p.drawn = true;
  for (size_t i = 0; i < 3; ++i) {
    const int64_t dx = p.x[(i + 1) % 3] - p.x[i], dy = p.y[(i + 1) % 3] - p.y[i];
    p.top_left[i] = dy < 0 || (dy == 0 && dx > 0);  // a left edge goes up, a top edge right
  }
  const DepthBias& bias = draw.state.depth_bias;
  if (!scene.has_depth() || !bias.enable) return p;
  // The plane's gradient in pixels: z = z0 + a (x - x0) + b (y - y0).
  const long double dx1 = p.x[1] - p.x[0], dy1 = p.y[1] - p.y[0], dx2 = p.x[2] - p.x[0], dy2 = p.y[2] - p.y[0];
  const long double dz1 = p.z[1] - p.z[0], dz2 = p.z[2] - p.z[0], area = (long double)cross;
  const long double units = std::ldexp(1.0L, int(gbits));
  const double a = double((dz1 * dy2 - dz2 * dy1) / area * units), b = double((dx1 * dz2 - dx2 * dz1) / area * units);
  const DepthFormatInfo info = depth_format_info(scene.depth_format);
  double r_low = std::ldexp(1.0, -int(info.bits)), r_high = 2 * r_low;
  if (info.encoding == DepthEncoding::Float) {
    double max_abs_z = 0;
    for (const WindowVertex& v : t.window) max_abs_z = std::max(max_abs_z, std::fabs(double(v.z)));
    r_low = float_depth_r(info, max_abs_z);
    r_high = 2 * r_low;
  }
  const double m_max = std::max(std::fabs(a), std::fabs(b)), m_sqrt = std::sqrt(a * a + b * b);
  for (const bool r_is_high : {false, true})
    for (const bool m_is_sqrt : {false, true})
      p.bias[bias_index(r_is_high, m_is_sqrt)] =
          dbclamp(double(bias.slope_factor) * (m_is_sqrt ? m_sqrt : m_max) +
                      double(bias.constant_factor) * (r_is_high ? r_high : r_low),
                  bias.clamp);
  return p;
}

// A triangle under every snapping rounding (index: SnapRounding).
struct Candidate {
  uint32_t owner = 0;
  const Draw* draw = nullptr;
  std::array<SnappedPlane, 3> plane;
};

Candidate make_candidate(const Scene& scene, const SpecTriangle& t, uint32_t bits) {
  Candidate c;
  c.owner = encode_owner(t.draw_index, t.primitive_index);
  c.draw = &scene.draws[t.draw_index];
  for (SnapRounding r : {SnapRounding::Nearest, SnapRounding::Floor, SnapRounding::Ceil})
    c.plane[size_t(r)] = snapped_plane(scene, t, bits, r);
  return c;
}

// The sample's position on the simulation grid.
struct GridSample {
  int64_t x = 0, y = 0;
};

GridSample grid_sample(const Scene& scene, uint32_t bits, uint32_t px, uint32_t py, uint32_t sample) {
  const uint32_t gbits = grid_bits(bits);
  const int64_t one = int64_t(1) << gbits;
  if (scene.samples == 1) return {px * one + one / 2, py * one + one / 2};
  const SampleOffset& s = kStandardSamples4x[sample];
  return {px * one + int64_t(std::ldexp(double(s.x), int(gbits))),
          py * one + int64_t(std::ldexp(double(s.y), int(gbits)))};
}

// The fragment depth, if the triangle covers the sample under the tie rule.
bool covers(const SnappedPlane& p, TieRule tie, GridSample s, long double& z) {
  std::array<Wide, 3> e{};
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3;
    e[i] = Wide(p.x[j] - p.x[i]) * (s.y - p.y[i]) - Wide(p.y[j] - p.y[i]) * (s.x - p.x[i]);
    if (e[i] < 0) return false;
    if (e[i] == 0 && p.top_left[i] != (tie == TieRule::TopLeft)) return false;
  }
  // Barycentric weight of vertex k: the edge opposite it over the area.
  z = ((long double)e[1] * p.z[0] + (long double)e[2] * p.z[1] + (long double)e[0] * p.z[2]) / (long double)p.area;
  return true;
}

// The stored value of a depth, as an ordered key: the UNORM integer (round to nearest), or the
// float (D32, rounded as the device rounds).
double stored_key(DepthFormat format, double z, FloatRounding rounding) {
  const DepthFormatInfo info = depth_format_info(format);
  if (info.encoding == DepthEncoding::Unorm) return std::nearbyint(std::clamp(z, 0.0, 1.0) * double(unorm_max(info)));
  float f = float(z);
  if (rounding == FloatRounding::Down && double(f) > z) f = std::nextafter(f, -INFINITY);
  if (rounding == FloatRounding::Up && double(f) < z) f = std::nextafter(f, INFINITY);
  return double(f);
}

// One device's owner of one sample: the triangles in draw order, each depth-tested against what
// the earlier ones left (Vulkan "Depth Test": a passing fragment writes its depth when writes are
// on; its owner is written whenever it passes).
uint32_t simulate_owner(const Scene& scene, const std::vector<const Candidate*>& candidates, const ExactDevice& device,
                        GridSample s) {
  const Viewport viewport = scene.effective_viewport();
  const double z_min = std::min(viewport.min_depth, viewport.max_depth);
  const double z_max = std::max(viewport.min_depth, viewport.max_depth);
  double stored = scene.has_depth() ? stored_key(scene.depth_format, scene.depth_clear, device.d32) : 0;
  uint32_t owner = kOwnerBackground;
  for (const Candidate* c : candidates) {
    const SnappedPlane& p = c->plane[size_t(device.snap)];
    long double z_plane = 0;
    if (!p.drawn || !covers(p, device.tie, s, z_plane)) continue;
    const RasterState& state = c->draw->state;
    const bool tested = scene.has_depth() && state.depth.test_enable;
    if (tested) {
      double z = double(z_plane) + p.bias[bias_index(device.bias_r_high, device.bias_m_sqrt)];
      if (state.depth_clamp) z = std::clamp(z, z_min, z_max);  // "Depth Clamping and Range Adjustment"
      const double key = stored_key(scene.depth_format, z, device.d32);
      if (!ordered_compare(state.depth.compare_op, key, stored)) continue;
      if (state.depth.write_enable) stored = key;
    }
    owner = c->owner;
  }
  return owner;
}

bool has_bias(const Scene& scene) {
  return std::any_of(scene.draws.begin(), scene.draws.end(), [](const Draw& d) {
    return d.state.depth_bias.enable &&
           (d.state.depth_bias.constant_factor != 0 || d.state.depth_bias.slope_factor != 0);
  });
}

std::vector<const Candidate*> all_candidates(const std::vector<Candidate>& candidates) {
  std::vector<const Candidate*> out;
  for (const Candidate& c : candidates) out.push_back(&c);
  return out;
}

}  // namespace

std::vector<ExactDevice> exact_devices(const Scene& scene) {
  std::vector<ExactDevice> devices;
  const std::array<std::pair<SnapRounding, TieRule>, 4> grids = {{{SnapRounding::Nearest, TieRule::TopLeft},
                                                                  {SnapRounding::Floor, TieRule::TopLeft},
                                                                  {SnapRounding::Ceil, TieRule::TopLeft},
                                                                  {SnapRounding::Nearest, TieRule::BottomRight}}};
  const bool bias = scene.has_depth() && has_bias(scene);
  const bool d32 = is_float(scene.depth_format);
  for (const auto& [snap_rounding, tie] : grids)
    for (const bool r_high : {false, true})
      for (const bool m_sqrt : {false, true}) {
        if ((r_high || m_sqrt) && !bias) continue;
        for (const FloatRounding f : {FloatRounding::Nearest, FloatRounding::Down, FloatRounding::Up}) {
          if (f != FloatRounding::Nearest && !d32) continue;
          devices.push_back({snap_rounding, tie, r_high, m_sqrt, f});
        }
      }
  return devices;
}

std::string describe_exact_device(const Scene& scene, const ExactDevice& device) {
  static constexpr std::array<const char*, 3> kSnap = {"nearest", "floor", "ceiling"};
  static constexpr std::array<const char*, 3> kD32 = {"nearest", "down", "up"};
  std::string text = std::string(kSnap[size_t(device.snap)]) + " vertex rounding, " +
                     (device.tie == TieRule::TopLeft ? "top-left" : "bottom-right") + " tie rule";
  if (scene.has_depth() && has_bias(scene))
    text += std::string(device.bias_r_high ? ", bias r at its upper end" : ", bias r at its lower end") +
            (device.bias_m_sqrt ? ", m in its sqrt form" : ", m in its max form");
  if (is_float(scene.depth_format)) text += std::string(", D32 rounding ") + kD32[size_t(device.d32)];
  return text;
}

std::vector<OwnerAlternative> exact_owner_alternatives(const Scene& scene, const std::vector<SpecTriangle>& triangles,
                                                       uint32_t sub_pixel_bits, const std::vector<uint32_t>& contested,
                                                       const PixelBuffer& estimate_owner) {
  std::vector<OwnerAlternative> out;
  if (contested.empty() || triangles.empty()) return out;
  const bool multisample = scene.samples > 1;
  const std::vector<ExactDevice> devices = exact_devices(scene);
  // The triangles whose boxes may touch each contested pixel, in draw order, as offsets into one
  // list (counted first, so that an over-large scene stops before allocating). Contested pixels
  // ascend, so each row's are a contiguous, sorted run.
  std::vector<uint32_t> offset(contested.size() + 1, 0), touching;
  const auto for_each_touch = [&](auto&& visit) {
    for (size_t ti = 0; ti < triangles.size(); ++ti) {
      const SnappedTriangle& s = triangles[ti].snapped;
      const PixelSpan xs = pixels_touching(s.x_min, s.x_max, sub_pixel_bits, multisample);
      const PixelSpan ys = pixels_touching(s.y_min, s.y_max, sub_pixel_bits, multisample);
      const int64_t y0 = std::max<int64_t>(ys.first, 0), y1 = std::min<int64_t>(ys.last, int64_t(scene.height) - 1);
      const int64_t x0 = std::max<int64_t>(xs.first, 0), x1 = std::min<int64_t>(xs.last, int64_t(scene.width) - 1);
      if (x0 > x1) continue;
      for (int64_t y = y0; y <= y1; ++y) {
        const uint32_t row = uint32_t(y) * scene.width;
        auto it = std::lower_bound(contested.begin(), contested.end(), row + uint32_t(x0));
        for (; it != contested.end() && *it <= row + uint32_t(x1); ++it)
          if (!visit(size_t(it - contested.begin()), uint32_t(ti))) return false;
      }
    }
    return true;
  };
  uint64_t work = 0;
  const uint64_t per_touch = uint64_t(scene.samples) * devices.size();
  const bool within = for_each_touch([&](size_t k, uint32_t) {
    ++offset[k + 1];
    work += per_touch;
    return work <= kExactOwnerWorkLimit;
  });
  if (!within) return out;
  for (size_t k = 0; k < contested.size(); ++k) offset[k + 1] += offset[k];
  touching.resize(offset.back());
  std::vector<uint32_t> fill(offset.begin(), offset.end() - 1);
  for_each_touch([&](size_t k, uint32_t ti) {
    touching[fill[k]++] = ti;
    return true;
  });
  // Each triangle that touches some contested pixel, under every snapping.
  std::vector<int32_t> slot(triangles.size(), -1);
  std::vector<Candidate> candidates;
  for (const uint32_t ti : touching)
    if (slot[ti] < 0) {
      slot[ti] = int32_t(candidates.size());
      candidates.push_back(make_candidate(scene, triangles[ti], sub_pixel_bits));
    }
  std::vector<const Candidate*> here;
  for (size_t k = 0; k < contested.size(); ++k) {
    if (offset[k + 1] - offset[k] < 2) continue;
    here.clear();
    for (uint32_t t = offset[k]; t < offset[k + 1]; ++t) here.push_back(&candidates[size_t(slot[touching[t]])]);
    const uint32_t px = contested[k] % scene.width, py = contested[k] / scene.width;
    for (uint32_t sample = 0; sample < scene.samples; ++sample) {
      const size_t index = (size_t(contested[k])) * scene.samples + sample;
      const GridSample s = grid_sample(scene, sub_pixel_bits, px, py, sample);
      const size_t first = out.size();
      for (const ExactDevice& device : devices) {
        const uint32_t owner = simulate_owner(scene, here, device, s);
        if (owner == kOwnerBackground || owner == estimate_owner[index]) continue;
        const OwnerAlternative alternative{uint64_t(index), owner};
        if (std::find(out.begin() + std::ptrdiff_t(first), out.end(), alternative) == out.end())
          out.push_back(alternative);
      }
      std::sort(out.begin() + std::ptrdiff_t(first), out.end(),
                [](const OwnerAlternative& a, const OwnerAlternative& b) { return a.owner < b.owner; });
    }
  }
  return out;
}

uint32_t exact_device_owner(const Scene& scene, const std::vector<SpecTriangle>& triangles, uint32_t sub_pixel_bits,
                            const ExactDevice& device, uint32_t x, uint32_t y, uint32_t sample) {
  std::vector<Candidate> candidates;
  for (const SpecTriangle& t : triangles) candidates.push_back(make_candidate(scene, t, sub_pixel_bits));
  return simulate_owner(scene, all_candidates(candidates), device, grid_sample(scene, sub_pixel_bits, x, y, sample));
}

std::vector<uint32_t> exact_device_owners(const Scene& scene, const std::vector<SpecTriangle>& triangles,
                                          uint32_t sub_pixel_bits, const ExactDevice& device) {
  std::vector<Candidate> candidates;
  for (const SpecTriangle& t : triangles) candidates.push_back(make_candidate(scene, t, sub_pixel_bits));
  const std::vector<const Candidate*> all = all_candidates(candidates);
  std::vector<uint32_t> owners(size_t(scene.width) * scene.height * scene.samples, kOwnerBackground);
  const PixelRect region = scissor_region(scene);
  for (int32_t y = region.y0; y <= region.y1; ++y)
    for (int32_t x = region.x0; x <= region.x1; ++x)
      for (uint32_t s = 0; s < scene.samples; ++s)
        owners[(size_t(y) * scene.width + size_t(x)) * scene.samples + s] =
            simulate_owner(scene, all, device, grid_sample(scene, sub_pixel_bits, uint32_t(x), uint32_t(y), s));
  return owners;
}

}  // namespace rastercmp::cpu::spec
