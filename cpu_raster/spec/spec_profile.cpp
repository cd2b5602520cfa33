#include "cpu_raster/spec/spec_profile.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cpu_raster/spec/coverage_map.hpp"
#include "cpu_raster/spec/depth_intervals.hpp"
#include "cpu_raster/spec/exact_owners.hpp"
#include "cpu_raster/spec/shared_edges.hpp"
#include "cpu_raster/spec/spec_primitives.hpp"
#include "model/errors.hpp"

namespace rastercmp {
namespace {

using namespace cpu::spec;

std::string draw_path(size_t d) { return "$.draws[" + std::to_string(d) + "]"; }

// Pixels of `region` whose boxes can touch the grid rectangle [x_lo, x_hi] x [y_lo, y_hi].
cpu::PixelRect pixels_near(int64_t x_lo, int64_t x_hi, int64_t y_lo, int64_t y_hi, uint32_t bits, bool multisample,
                           const cpu::PixelRect& region) {
  const PixelSpan xs = pixels_touching(x_lo, x_hi, bits, multisample);
  const PixelSpan ys = pixels_touching(y_lo, y_hi, bits, multisample);
  return cpu::PixelRect{int32_t(std::max<int64_t>(xs.first, region.x0)),
                        int32_t(std::max<int64_t>(ys.first, region.y0)), int32_t(std::min<int64_t>(xs.last, region.x1)),
                        int32_t(std::min<int64_t>(ys.last, region.y1))};
}

cpu::PixelRect triangle_pixels(const SnappedTriangle& t, uint32_t bits, bool multisample,
                               const cpu::PixelRect& region) {
  return pixels_near(t.x_min, t.x_max, t.y_min, t.y_max, bits, multisample, region);
}

// The viewport rectangle in window pixels: the image of the clip volume -w_c <= x_c, y_c <= w_c
// (Vulkan "Primitive Clipping", "Controlling the Viewport"), where every clipped primitive lies.
struct ViewportRect {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};

ViewportRect viewport_rect(const Viewport& v) {
  const double y_end = double(v.y) + double(v.height);
  return {double(v.x), double(v.x) + double(v.width), std::min(double(v.y), y_end), std::max(double(v.y), y_end)};
}

// The box lies strictly inside the viewport rectangle: its sides bound a triangle's clipped
// polygon as its edges do, so a box across them cannot be FULL (the same rule as for lines).
bool box_inside_viewport(const ViewportRect& r, const ToleranceBox& box, uint32_t bits) {
  const double unit = std::ldexp(1.0, -int(bits));
  const double x0 = double(box.cx - box.half) * unit, x1 = double(box.cx + box.half) * unit;
  const double y0 = double(box.cy - box.half) * unit, y1 = double(box.cy + box.half) * unit;
  return x0 > r.x0 && x1 < r.x1 && y0 > r.y0 && y1 < r.y1;
}

// FULL only for a piece whose shape is certain, and inside the viewport rectangle.
Coverage capped(Coverage coverage, const SpecTriangle& t, const ViewportRect& viewport, const ToleranceBox& box,
                uint32_t bits) {
  if (coverage != Coverage::Full) return coverage;
  return t.shape_certain && box_inside_viewport(viewport, box, bits) ? Coverage::Full : Coverage::Partial;
}

// The depth a primitive may write at pixel (px, py), where it may cover the pixel with `gate`. A
// gate of Never (the fragment fails against the clear value) still counts: the fragment may pass
// against a value an earlier draw wrote (a GREATER probe over a LESS-drawn quad).
void add_depth(DepthIntervalMap* depths, const DepthJudge& judge, int32_t px, int32_t py, Coverage coverage,
               Gate gate) {
  if (depths == nullptr || !judge.writes || coverage == Coverage::None) return;
  depths->add(px, py, fragment_depth_range(judge, glm::dvec2(px + 0.5, py + 0.5)),
              coverage == Coverage::Full && gate == Gate::Certain);
}

// Per pixel, how many triangles may cover it (saturating): where two or more may, the owner is
// contested (exact_owners.hpp).
using TouchCounts = std::vector<uint8_t>;

// Row by row: whole FULL spans at once, classify_box only near the edges.
void add_triangle(CoverageMap& map, DepthIntervalMap* depths, TouchCounts* touches, const SpecTriangle& t,
                  const ViewportRect& viewport, uint32_t bits, bool multisample, uint32_t width) {
  const cpu::PixelRect r = triangle_pixels(t.snapped, bits, multisample, map.region());
  for (int32_t py = r.y0; py <= r.y1; ++py) {
    const RowSpans spans = row_spans(t.snapped, py, bits, multisample);
    const int64_t first = std::max<int64_t>(spans.touch_first, r.x0), last = std::min<int64_t>(spans.touch_last, r.x1);
    for (int64_t x = first; x <= last; ++x) {
      const int32_t px = int32_t(x);
      const ToleranceBox box = pixel_box(px, py, bits, multisample);
      const Coverage coverage = capped((x >= spans.full_first && x <= spans.full_last) ? Coverage::Full
                                                                                       : classify_box(t.snapped, box),
                                       t, viewport, box, bits);
      if (coverage == Coverage::None) continue;
      const Gate gate = triangle_gate_at(t, px, py);
      map.add(px, py, coverage, gate);
      add_depth(depths, t.depth, px, py, coverage, gate);
      if (touches != nullptr) {
        uint8_t& n = (*touches)[size_t(py) * width + size_t(px)];
        if (n < 2) ++n;
      }
    }
  }
}

void add_shared_edge(CoverageMap& map, const std::vector<SpecTriangle>& triangles, const SharedEdge& shared,
                     const ViewportRect& viewport, uint32_t bits, bool multisample) {
  if (!triangles[shared.first].shape_certain || !triangles[shared.second].shape_certain) return;
  const cpu::PixelRect r =
      cpu::intersect(triangle_pixels(triangles[shared.first].snapped, bits, multisample, map.region()),
                     triangle_pixels(triangles[shared.second].snapped, bits, multisample, map.region()));
  for (int32_t py = r.y0; py <= r.y1; ++py)
    for (int32_t px = r.x0; px <= r.x1; ++px)
      if (!map.is_must(px, py) && box_inside_viewport(viewport, pixel_box(px, py, bits, multisample), bits) &&
          promoted(triangles, shared, pixel_box(px, py, bits, multisample)) &&
          triangle_gate_at(triangles[shared.first], px, py) == Gate::Certain &&
          triangle_gate_at(triangles[shared.second], px, py) == Gate::Certain)
        map.make_must(px, py);
}

// Row by row: only the columns where the May quads cross the band of the row's grown boxes.
void add_line(CoverageMap& map, DepthIntervalMap* depths, const SpecLine& line, uint32_t bits, bool multisample) {
  const double half_px = std::ldexp(double(pixel_box(0, 0, bits, multisample).half), -int(bits));
  const double reach = half_px + kLineMarginPx;  // the grown square's half-size
  const PixelBounds b = may_bounds(line.shape);
  const cpu::PixelRect& region = map.region();
  const int32_t y_first = int32_t(std::max(double(region.y0), std::ceil(b.y_min - half_px - 0.5)));
  const int32_t y_last = int32_t(std::min(double(region.y1), std::floor(b.y_max + half_px - 0.5)));
  for (int32_t py = y_first; py <= y_last; ++py) {
    const XExtent e = may_extent_in_band(line.shape, py + 0.5 - reach, py + 0.5 + reach);
    if (e.x_min > e.x_max) continue;
    const int32_t x_first = int32_t(std::max(double(region.x0), std::ceil(e.x_min - reach - 0.5)));
    const int32_t x_last = int32_t(std::min(double(region.x1), std::floor(e.x_max + reach - 0.5)));
    for (int32_t px = x_first; px <= x_last; ++px) {
      const PixelSquare box{glm::dvec2(px + 0.5, py + 0.5), half_px};
      const Coverage coverage = classify_line_box(line.shape, box);
      if (coverage == Coverage::None) continue;
      const Gate gate = depth_gate_at(line.depth, box.centre);
      map.add(px, py, coverage, gate);
      add_depth(depths, line.depth, px, py, coverage, gate);
    }
  }
}

}  // namespace

void check_spec_profile_support(const Scene& scene) {
  for (size_t d = 0; d < scene.draws.size(); ++d) {
    const Draw& draw = scene.draws[d];
    for (size_t k = 0; k < draw.indices.size(); ++k)
      if (draw.indices[k] >= draw.positions_clip.size())
        throw InputError(scene.source_path, draw_path(d) + ".indices[" + std::to_string(k) + "]",
                         "expected an index below the number of positions");
    if (draw.topology == Topology::PointList)
      throw NotSupportedError(draw_path(d) + ": point_list is not classified by the CPU spec profile");
    if (is_triangle_topology(draw.topology) && draw.state.polygon_mode != PolygonMode::Fill)
      throw NotSupportedError(draw_path(d) + ": polygon_mode \"" + to_string(draw.state.polygon_mode) +
                              "\" is not classified by the CPU spec profile");
    if (is_line_topology(draw.topology) && draw.state.line_mode == LineMode::RectangularSmooth)
      throw NotSupportedError(draw_path(d) +
                              ": line_mode \"rectangular_smooth\" is not classified by the CPU spec "
                              "profile (smooth-line coverage is an implementation's alpha)");
  }
}

namespace {

// What the owner alternatives need from the classification.
struct Contest {
  TouchCounts touches;
  SpecPrimitives primitives;
  bool simulated = false;  // triangles only, none undefined: exact_owners.hpp can simulate them
};

// Classes, and with `depths` the depth intervals, of the union of all draws; with `contest`, what
// exact_owner_alternatives needs.
std::vector<CoverageClass> classify(const Scene& scene, const CpuOptions& options, DepthIntervalMap* depths,
                                    Contest* contest = nullptr) {
  check_spec_profile_support(scene);
  const uint32_t bits = effective_sub_pixel_bits(options.sub_pixel_bits);
  const bool multisample = scene.samples > 1;
  CoverageMap map(scene);
  if (map.region().empty()) return map.classes();
  SpecPrimitives primitives = build_spec_primitives(scene, options.fma, bits);
  if (primitives.undefined) {
    map.make_may_everywhere();
    if (depths != nullptr) depths->make_any(map.region());
  }
  TouchCounts* touches = nullptr;
  if (contest != nullptr && !primitives.undefined && primitives.lines.empty()) {
    contest->touches.assign(size_t(scene.width) * scene.height, 0);
    touches = &contest->touches;
  }
  const ViewportRect viewport = viewport_rect(scene.effective_viewport());
  for (const SpecTriangle& t : primitives.triangles)
    add_triangle(map, depths, touches, t, viewport, bits, multisample, scene.width);
  for (const SharedEdge& shared : find_shared_edges(primitives.triangles))
    add_shared_edge(map, primitives.triangles, shared, viewport, bits, multisample);
  for (const SpecLine& line : primitives.lines) add_line(map, depths, line, bits, multisample);
  if (touches != nullptr) {
    // Only Must pixels: a May sample takes any owner anyway.
    for (size_t i = 0; i < contest->touches.size(); ++i)
      if (contest->touches[i] >= 2 && !map.is_must(int32_t(i % scene.width), int32_t(i / scene.width)))
        contest->touches[i] = 0;
    contest->primitives = std::move(primitives);
    contest->simulated = true;
  }
  return map.classes();
}

}  // namespace

std::vector<CoverageClass> spec_coverage_classes(const Scene& scene, const CpuOptions& options) {
  return classify(scene, options, nullptr);
}

RenderResult render_spec_profile(const Scene& scene, const CpuOptions& options, RenderResult estimate) {
  check_spec_profile_support(scene);
  RenderResult result = std::move(estimate);
  result.device = "cpu spec profile (subPixelPrecisionBits " + std::to_string(options.sub_pixel_bits) + ")";
  DepthIntervalMap depths(scene);
  Contest contest;
  result.coverage_class = classify(scene, options, &depths, &contest);
  result.depth_interval = depths.intervals();
  if (contest.simulated) {
    std::vector<uint32_t> contested;
    for (size_t i = 0; i < contest.touches.size(); ++i)
      if (contest.touches[i] >= 2) contested.push_back(uint32_t(i));
    result.owner_alternatives =
        exact_owner_alternatives(scene, contest.primitives.triangles, effective_sub_pixel_bits(options.sub_pixel_bits),
                                 contested, result.owner);
  }
  return result;
}

}  // namespace rastercmp
