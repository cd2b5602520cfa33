#include "cpu_raster/spec/spec_profile.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

#include "cpu_raster/spec/coverage_map.hpp"
#include "cpu_raster/spec/depth_intervals.hpp"
#include "cpu_raster/spec/exact_owners.hpp"
#include "cpu_raster/spec/open_owners.hpp"
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
      const Coverage coverage =
          capped((x >= spans.full_first && x <= spans.full_last) ? Coverage::Full : classify_box(t.snapped, box), t,
                 viewport, box, bits);
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
  const double half_px = pixel_box_half_px(bits, multisample);
  const cpu::PixelRect& region = map.region();
  const IndexSpan rows = line_rows(line.shape, half_px, region.y0, region.y1);
  for (int32_t py = rows.first; py <= rows.last; ++py) {
    const IndexSpan columns = line_columns(line.shape, half_px, py, region.x0, region.x1);
    for (int32_t px = columns.first; px <= columns.last; ++px) {
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
  bool simulated = false;  // none undefined: exact_owners.hpp can simulate the triangles
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
  if (contest != nullptr && !primitives.undefined) {
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

namespace {

// What the profile judges a render by, for one viewport.
struct Judgement {
  std::vector<CoverageClass> classes;
  std::vector<DepthInterval> intervals;
  std::vector<OwnerAlternative> alternatives;
};

bool alternative_before(const OwnerAlternative& a, const OwnerAlternative& b) {
  return a.sample != b.sample ? a.sample < b.sample : a.owner < b.owner;
}

Judgement judge(const Scene& scene, const CpuOptions& options, const PixelBuffer& estimate_owner) {
  Judgement j;
  DepthIntervalMap depths(scene);
  Contest contest;
  j.classes = classify(scene, options, &depths, &contest);
  j.intervals = depths.intervals();
  if (!contest.simulated) return j;
  const uint32_t bits = effective_sub_pixel_bits(options.sub_pixel_bits);
  std::vector<uint32_t> contested;
  for (size_t i = 0; i < contest.touches.size(); ++i)
    if (contest.touches[i] >= 2) contested.push_back(uint32_t(i));
  // Where the owner is open (open_owners.hpp) its rule replaces the simulated devices'.
  const std::vector<uint32_t> open = open_owner_pixels(scene, contest.primitives, j.classes, estimate_owner, bits);
  std::vector<OwnerAlternative> simulated =
      exact_owner_alternatives(scene, contest.primitives.triangles, bits, contested, estimate_owner);
  std::erase_if(simulated, [&](const OwnerAlternative& a) {
    return std::binary_search(open.begin(), open.end(), uint32_t(a.sample / scene.samples));
  });
  const std::vector<OwnerAlternative> opened =
      open_owner_alternatives(scene, contest.primitives, bits, open, estimate_owner);
  j.alternatives.resize(simulated.size() + opened.size());
  std::merge(simulated.begin(), simulated.end(), opened.begin(), opened.end(), j.alternatives.begin(),
             alternative_before);
  return j;
}

// The judgement a device with any of the representations passes: Must or MustNot where every
// representation says so, May elsewhere; the hull of the depth intervals; every alternative owner
// (a relaxation per sample, like the classes themselves).
void widen(Judgement& into, const Judgement& other, DepthFormat format) {
  for (size_t i = 0; i < into.classes.size(); ++i)
    if (into.classes[i] != other.classes[i]) into.classes[i] = CoverageClass::May;
  for (size_t i = 0; i < into.intervals.size(); ++i) {
    DepthInterval& a = into.intervals[i];
    const DepthInterval& b = other.intervals[i];
    if (b.any) a.any = true;
    if (depth_raw_order(format, b.lo_raw) < depth_raw_order(format, a.lo_raw)) {
      a.lo_raw = b.lo_raw;
      a.lo_term = b.lo_term;
    }
    if (depth_raw_order(format, b.hi_raw) > depth_raw_order(format, a.hi_raw)) {
      a.hi_raw = b.hi_raw;
      a.hi_term = b.hi_term;
    }
  }
  std::vector<OwnerAlternative> merged;
  std::set_union(into.alternatives.begin(), into.alternatives.end(), other.alternatives.begin(),
                 other.alternatives.end(), std::back_inserter(merged), alternative_before);
  into.alternatives = std::move(merged);
}

}  // namespace

std::vector<Viewport> spec_viewport_representations(const Scene& scene, const CpuOptions& options) {
  const Viewport v = scene.effective_viewport();
  const uint32_t viewport_bits = options.viewport_sub_pixel_bits;
  const double unit = std::ldexp(1.0, -int(std::min<uint32_t>(viewport_bits, 16)));
  const auto both = [unit](float value) {
    const double scaled = double(value) / unit;
    return std::array<float, 2>{float(std::floor(scaled) * unit), float(std::ceil(scaled) * unit)};
  };
  const std::array<float, 2> xs = both(v.x), ys = both(v.y), ws = both(v.width), hs = both(v.height);
  const auto same_bounds = [](const Viewport& a, const Viewport& b) {
    return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
  };
  std::vector<Viewport> out;
  for (const float x : xs)
    for (const float y : ys)
      for (const float w : ws)
        for (const float h : hs) {
          const Viewport r{x, y, w, h, v.min_depth, v.max_depth};
          const bool seen = same_bounds(r, v) ||
                            std::any_of(out.begin(), out.end(), [&](const Viewport& o) { return same_bounds(o, r); });
          if (!seen && r.width != 0 && r.height != 0) out.push_back(r);
        }
  return out;
}

RenderResult render_spec_profile(const Scene& scene, const CpuOptions& options, RenderResult estimate) {
  check_spec_profile_support(scene);
  RenderResult result = std::move(estimate);
  result.device = "cpu spec profile (subPixelPrecisionBits " + std::to_string(options.sub_pixel_bits) + ")";
  Judgement j = judge(scene, options, result.owner);
  for (const Viewport& v : spec_viewport_representations(scene, options)) {
    Scene represented = scene;
    represented.viewport = v;
    widen(j, judge(represented, options, result.owner), scene.depth_format);
  }
  // Alternatives name Must samples only.
  std::erase_if(j.alternatives, [&](const OwnerAlternative& a) { return j.classes[a.sample] != CoverageClass::Must; });
  result.coverage_class = std::move(j.classes);
  result.depth_interval = std::move(j.intervals);
  result.owner_alternatives = std::move(j.alternatives);
  return result;
}

}  // namespace rastercmp
