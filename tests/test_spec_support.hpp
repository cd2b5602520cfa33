// Shared pieces of the spec-profile tests (tests/test_spec_*.cpp): scenes in window pixels, the
// count of spec violations of a render, and a readable description of the first one.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/raster_primitive.hpp"
#include "cpu_raster/spec/spec_primitives.hpp"
#include "cpu_raster/spec/spec_profile.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp::spec_test {

// Window (x, y) → clip position for the default viewport of a w x h scene: exact for
// power-of-two sizes (2x/w - 1 and the driver's (w/2) x_c + w/2 round nowhere).
inline glm::vec4 clip_from_window(double x, double y, float z, uint32_t w, uint32_t h) {
  return {float(2.0 * x / w - 1.0), float(2.0 * y / h - 1.0), z, 1.0f};
}

inline Scene make_scene(uint32_t w, uint32_t h, uint32_t samples = 1) {
  Scene scene;
  scene.name = "test.spec_profile";
  scene.width = w;
  scene.height = h;
  scene.samples = samples;
  return scene;
}

// A triangle list from window-space vertices at depth z.
inline Draw window_triangles(const Scene& scene, const std::vector<glm::dvec2>& xy, float z = 0.5f) {
  Draw draw;
  for (const glm::dvec2& p : xy)
    draw.positions_clip.push_back(clip_from_window(p.x, p.y, z, scene.width, scene.height));
  return draw;
}

inline CpuOptions lavapipe_options(const LavapipeRelease& release = lavapipe_releases().front()) {
  CpuOptions o;
  o.profile = CpuProfile::Lavapipe;
  o.lavapipe = &release;
  return o;
}

inline CpuOptions spec_options(uint32_t bits = 8) {
  CpuOptions o;
  o.profile = CpuProfile::Spec;
  o.sub_pixel_bits = bits;
  return o;
}

struct Violations {
  uint64_t must_missing = 0, must_not_covered = 0;
  uint64_t depth_outside = 0;                // Must or May samples whose depth is outside the interval
  uint64_t must = 0, may = 0, must_not = 0;  // the class counts
  std::string first;                         // "" when there is none
  bool any() const { return must_missing + must_not_covered + depth_outside > 0; }
};

// Judges `owner` (RenderResult layout) by `classes` as the CTS verifier does.
inline Violations judge(const std::vector<CoverageClass>& classes, const RenderResult& render) {
  Violations v;
  for (uint32_t y = 0; y < render.height; ++y)
    for (uint32_t x = 0; x < render.width; ++x)
      for (uint32_t s = 0; s < render.samples; ++s) {
        const size_t i = render.index(x, y, s);
        const bool covered = render.owner[i] != kOwnerBackground;
        const CoverageClass c = classes[i];
        v.must += c == CoverageClass::Must;
        v.may += c == CoverageClass::May;
        v.must_not += c == CoverageClass::MustNot;
        const bool missing = c == CoverageClass::Must && !covered;
        const bool unexpected = c == CoverageClass::MustNot && covered;
        v.must_missing += missing;
        v.must_not_covered += unexpected;
        if ((missing || unexpected) && v.first.empty())
          v.first = fmt::format("first at ({}, {}) sample {}: {}", x, y, s,
                                missing ? "Must but uncovered" : "MustNot but covered");
      }
  return v;
}

// judge(classes, render), and the stored depth of every Must and May sample against the spec
// profile's intervals.
inline Violations judge(const RenderResult& spec, const RenderResult& render) {
  Violations v = judge(spec.coverage_class, render);
  if (spec.depth_interval.empty() || !render.has_depth()) return v;
  for (size_t i = 0; i < render.depth_raw.size(); ++i) {
    const bool covered = render.owner[i] != kOwnerBackground;
    if (spec.coverage_class[i] == CoverageClass::MustNot) continue;
    if (spec.coverage_class[i] == CoverageClass::Must && !covered) continue;  // missing: counted as coverage
    const DepthInterval& d = spec.depth_interval[i];
    if (depth_in_interval(render.depth_format, d, render.depth_raw[i])) continue;
    if (++v.depth_outside == 1) {
      const size_t pixel = i / render.samples;
      v.first +=
          fmt::format(" depth at ({}, {}) sample {} owner {:#x}: {} outside [{}, {}] (lo: {}, hi: {})",
                      pixel % render.width, pixel / render.width, i % render.samples, render.owner[i],
                      depth_raw_to_value(render.depth_format, render.depth_raw[i]),
                      depth_raw_to_value(render.depth_format, d.lo_raw),
                      depth_raw_to_value(render.depth_format, d.hi_raw), to_string(d.lo_term), to_string(d.hi_term));
    }
  }
  return v;
}

// docs/spec-profile.md "Lavapipe deviations", depth extrapolated past the vertices: lavapipe
// interpolates depth over the plane through the unsnapped float window vertices
// (docs/lavapipe-rules.md §3.2) but covers samples with the vertices snapped to 1/256 px (§2.2), so
// a sample that the snapped triangle covers but the float one does not gets the plane's value
// outside the triangle, past the vertices' depth range, which "Basic Polygon Rasterization" rules
// out (barycentric coordinates "each in the range [0,1]"; a clipped polygon's fragments a convex
// combination of its vertices' values). Per sample whose stored depth lies outside its interval:
// when some depth-writing piece's float triangle misses the sample (lavapipe's sample location) by
// at most what lavapipe's snapping moves a vertex (sqrt(2)/256 px), and the stored value lies in
// the interval the profile computes for that piece with its vertex depth range stretched to the
// float plane's value at the sample, that is this deviation: the sample's interval in `spec` is
// widened to the stored value. Returns how many samples were.
inline uint64_t accept_float_plane_extrapolation(const Scene& scene, uint32_t bits, RenderResult& spec,
                                                 const RenderResult& exact) {
  if (spec.depth_interval.empty() || !exact.has_depth()) return 0;
  const cpu::spec::SpecPrimitives primitives = cpu::spec::build_spec_primitives(scene, spec_options(bits).fma, bits);
  const double reach = std::sqrt(2.0) / 256.0;
  uint64_t accepted = 0;
  for (size_t i = 0; i < exact.depth_raw.size(); ++i) {
    if (spec.coverage_class[i] == CoverageClass::MustNot || exact.owner[i] == kOwnerBackground) continue;
    DepthInterval& d = spec.depth_interval[i];
    const uint32_t raw = exact.depth_raw[i];
    if (depth_in_interval(exact.depth_format, d, raw)) continue;
    const size_t pixel = i / exact.samples;
    const uint32_t px = uint32_t(pixel % exact.width), py = uint32_t(pixel / exact.width),
                   s = uint32_t(i % exact.samples);
    const glm::dvec2 p = exact.samples > 1
                             ? glm::dvec2(px + cpu::kStandardSamples4x[s].x, py + cpu::kStandardSamples4x[s].y)
                             : glm::dvec2(px + 0.5, py + 0.5);
    for (const cpu::spec::SpecTriangle& t : primitives.triangles) {
      if (!t.depth.writes || !t.depth.plane_defined || t.depth.bias_any) continue;
      const auto area = [](glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
        return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      };
      glm::dvec2 v[3];
      for (size_t k = 0; k < 3; ++k) v[k] = glm::dvec2(t.window[k].x, t.window[k].y);
      const double whole = area(v[0], v[1], v[2]);
      if (whole == 0) continue;
      double z = 0, outside = 0;
      for (size_t k = 0; k < 3; ++k) {
        const glm::dvec2 b = v[(k + 1) % 3], c = v[(k + 2) % 3];
        const double weight = area(p, b, c) / whole;
        z += weight * double(t.window[k].z);
        const double edge = std::hypot(c.x - b.x, c.y - b.y);
        if (weight < 0 && edge > 0) outside = std::max(outside, -weight * std::fabs(whole) / edge);
      }
      if (outside == 0 || outside > reach) continue;  // inside the float triangle, or too far to be covered
      cpu::spec::DepthJudge stretched = t.depth;
      stretched.vertex_lo = std::min(stretched.vertex_lo, z);
      stretched.vertex_hi = std::max(stretched.vertex_hi, z);
      const DepthInterval widened = cpu::spec::depth_format_interval(
          exact.depth_format, cpu::spec::fragment_depth_range(stretched, glm::dvec2(px + 0.5, py + 0.5)));
      if (!depth_in_interval(exact.depth_format, widened, raw)) continue;
      d.lo_raw = std::min(d.lo_raw, raw);
      d.hi_raw = std::max(d.hi_raw, raw);
      ++accepted;
      break;
    }
  }
  return accepted;
}

inline std::string describe(const Violations& v) {
  return fmt::format("{} Must-missing, {} MustNot-covered, {} depth outside (Must {}, May {}, MustNot {}) {}",
                     v.must_missing, v.must_not_covered, v.depth_outside, v.must, v.may, v.must_not, v.first);
}

// The scene in a few lines, for a failing property's log.
inline std::string describe(const Scene& scene) {
  const Viewport v = scene.effective_viewport();
  const Rect2D sc = scene.effective_scissor();
  std::string text =
      fmt::format("{}x{} samples {} depth {} clear {} viewport ({}, {}, {}, {}, {}..{}) scissor ({}, {}, {}, {})\n",
                  scene.width, scene.height, scene.samples, to_string(scene.depth_format), scene.depth_clear, v.x, v.y,
                  v.width, v.height, v.min_depth, v.max_depth, sc.x, sc.y, sc.width, sc.height);
  for (const Draw& d : scene.draws) {
    const RasterState& s = d.state;
    text += fmt::format("draw {} cull {} front {} test {} op {} bias {} ({}, {}, {}) clamp {} clip {} line {} w {}\n",
                        to_string(d.topology), to_string(s.cull_mode), to_string(s.front_face), s.depth.test_enable,
                        to_string(s.depth.compare_op), s.depth_bias.enable, s.depth_bias.constant_factor,
                        s.depth_bias.slope_factor, s.depth_bias.clamp, s.depth_clamp, s.depth_clip_enabled(),
                        to_string(s.line_mode), s.line_width);
    for (const glm::vec4& p : d.positions_clip) text += fmt::format("  [{}, {}, {}, {}]\n", p.x, p.y, p.z, p.w);
    if (!d.indices.empty()) {
      text += "  indices";
      for (uint32_t i : d.indices) text += fmt::format(" {}", i);
      text += "\n";
    }
  }
  return text;
}

}  // namespace rastercmp::spec_test
