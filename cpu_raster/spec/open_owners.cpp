#include "cpu_raster/spec/open_owners.hpp"

#include <algorithm>
#include <cmath>

#include "cpu_raster/spec/coverage_map.hpp"
#include "cpu_raster/spec/subpixel.hpp"

namespace rastercmp::cpu::spec {
namespace {

// One primitive (a triangle piece or a line) in submission order: owner ids order like
// (draw, primitive), and a clipped triangle's pieces share theirs.
struct PrimitiveRef {
  uint32_t owner = 0;
  const SpecTriangle* triangle = nullptr;
  const SpecLine* line = nullptr;

  const DepthJudge& depth() const { return triangle != nullptr ? triangle->depth : line->depth; }
  uint32_t draw_index() const { return triangle != nullptr ? triangle->draw_index : line->draw_index; }
};

std::vector<PrimitiveRef> submission_order(const SpecPrimitives& primitives) {
  std::vector<PrimitiveRef> refs;
  for (const SpecTriangle& t : primitives.triangles)
    refs.push_back({encode_owner(t.draw_index, t.primitive_index), &t, nullptr});
  for (const SpecLine& l : primitives.lines)
    refs.push_back({encode_owner(l.draw_index, l.primitive_index), nullptr, &l});
  std::stable_sort(refs.begin(), refs.end(),
                   [](const PrimitiveRef& a, const PrimitiveRef& b) { return a.owner < b.owner; });
  return refs;
}

// The pixels whose boxes may touch the primitive, within the framebuffer (may be empty); a line's
// columns, row by row, are line_columns.
PixelRect reach(const Scene& scene, const PrimitiveRef& ref, uint32_t bits, bool multisample) {
  const int32_t x_max = int32_t(scene.width) - 1, y_max = int32_t(scene.height) - 1;
  if (ref.line != nullptr) {
    const double half_px = pixel_box_half_px(bits, multisample);
    const PixelBounds b = may_bounds(ref.line->shape);
    const IndexSpan rows = line_rows(ref.line->shape, half_px, 0, y_max);
    return PixelRect{int32_t(std::clamp(std::ceil(b.x_min - half_px - 0.5), 0.0, double(x_max) + 1)), rows.first,
                     int32_t(std::clamp(std::floor(b.x_max + half_px - 0.5), -1.0, double(x_max))), rows.last};
  }
  const SnappedTriangle& s = ref.triangle->snapped;
  const PixelSpan xs = pixels_touching(s.x_min, s.x_max, bits, multisample);
  const PixelSpan ys = pixels_touching(s.y_min, s.y_max, bits, multisample);
  return PixelRect{int32_t(std::max<int64_t>(xs.first, 0)), int32_t(std::max<int64_t>(ys.first, 0)),
                   int32_t(std::min<int64_t>(xs.last, x_max)), int32_t(std::min<int64_t>(ys.last, y_max))};
}

Coverage coverage_at(const PrimitiveRef& ref, const ViewportRect& viewport, int32_t px, int32_t py, uint32_t bits,
                     bool multisample) {
  return ref.triangle != nullptr ? triangle_coverage_at(*ref.triangle, viewport, px, py, bits, multisample)
                                 : line_coverage_at(*ref.line, px, py, bits, multisample);
}

Gate gate_at(const PrimitiveRef& ref, int32_t px, int32_t py) {
  return ref.triangle != nullptr ? triangle_gate_at(*ref.triangle, px, py)
                                 : depth_gate_at(ref.line->depth, glm::dvec2(px + 0.5, py + 0.5));
}

bool any_sample_must(const std::vector<CoverageClass>& classes, size_t pixel, uint32_t samples) {
  for (uint32_t s = 0; s < samples; ++s)
    if (classes[pixel * samples + s] == CoverageClass::Must) return true;
  return false;
}

// Which way a compare op lets the stored depth move when it passes and writes.
enum class Direction : uint8_t { Down, Up, Either };

Direction direction(CompareOp op) {
  switch (op) {
    case CompareOp::Less:
    case CompareOp::LessOrEqual: return Direction::Down;
    case CompareOp::Greater:
    case CompareOp::GreaterOrEqual: return Direction::Up;
    default: return Direction::Either;
  }
}

bool writes_depth(const Scene& scene, const Draw& draw) {
  return scene.has_depth() && draw.state.depth.test_enable && draw.state.depth.write_enable;
}

// Draw d's depth writes keep the stored value from moving against `dir` (EQUAL writes what is
// there, NEVER writes nothing).
bool keeps(const Scene& scene, const Draw& draw, Direction dir) {
  if (!writes_depth(scene, draw)) return true;
  const CompareOp op = draw.state.depth.compare_op;
  return op == CompareOp::Equal || op == CompareOp::Never || direction(op) == dir;
}

// A fragment of one primitive at one open pixel.
struct Fragment {
  const PrimitiveRef* ref = nullptr;
  bool certain = false;  // FULL with a certain gate
  DepthInterval interval;
};

class BeatRule {
 public:
  explicit BeatRule(const Scene& scene) : scene_(scene) {
    // breaks_[dir][d]: how many of draws 0..d-1 may move the stored value against dir.
    for (const Direction dir : {Direction::Down, Direction::Up}) {
      std::vector<uint32_t>& b = breaks_[size_t(dir)];
      b.assign(scene.draws.size() + 1, 0);
      for (size_t d = 0; d < scene.draws.size(); ++d) b[d + 1] = b[d] + (keeps(scene, scene.draws[d], dir) ? 0 : 1);
    }
  }

  // Whether fragment c, certainly there, leaves p no way to be the sample's last passing fragment.
  bool certainly_beats(const Fragment& c, const Fragment& p) const {
    const Draw& dc = scene_.draws[c.ref->draw_index()];
    const Draw& dp = scene_.draws[p.ref->draw_index()];
    if (c.ref->owner > p.ref->owner) {  // c comes later
      if (!scene_.has_depth() || !dc.state.depth.test_enable || dc.state.depth.compare_op == CompareOp::Always)
        return true;
      if (!writes_depth(scene_, dp) || c.interval.any || p.interval.any) return false;
      switch (dc.state.depth.compare_op) {
        case CompareOp::Less: return key(c.interval.hi_raw) < key(p.interval.lo_raw);
        case CompareOp::LessOrEqual: return key(c.interval.hi_raw) <= key(p.interval.lo_raw);
        case CompareOp::Greater: return key(c.interval.lo_raw) > key(p.interval.hi_raw);
        case CompareOp::GreaterOrEqual: return key(c.interval.lo_raw) >= key(p.interval.hi_raw);
        default: return false;
      }
    }
    // c comes first: it bounds the stored value p meets.
    if (!scene_.has_depth() || !dp.state.depth.test_enable || !writes_depth(scene_, dc)) return false;
    if (c.interval.any || p.interval.any) return false;
    const Direction dir = direction(dc.state.depth.compare_op);
    if (dir == Direction::Either) return false;
    const std::vector<uint32_t>& b = breaks_[size_t(dir)];
    if (b[p.ref->draw_index() + 1] != b[c.ref->draw_index()]) return false;
    const CompareOp op = dp.state.depth.compare_op;
    if (dir == Direction::Down) {  // stored <= c's upper bound
      const int64_t bound = key(c.interval.hi_raw), lo = key(p.interval.lo_raw);
      if (op == CompareOp::Less) return lo >= bound;
      if (op == CompareOp::LessOrEqual || op == CompareOp::Equal) return lo > bound;
      return false;
    }
    const int64_t bound = key(c.interval.lo_raw), hi = key(p.interval.hi_raw);  // stored >= c's lower bound
    if (op == CompareOp::Greater) return hi <= bound;
    if (op == CompareOp::GreaterOrEqual || op == CompareOp::Equal) return hi < bound;
    return false;
  }

 private:
  int64_t key(uint32_t raw) const { return depth_raw_order(scene_.depth_format, raw); }

  const Scene& scene_;
  std::array<std::vector<uint32_t>, 2> breaks_;
};

}  // namespace

std::vector<uint32_t> open_owner_pixels(const Scene& scene, const SpecPrimitives& primitives,
                                        const std::vector<CoverageClass>& classes, const PixelBuffer& estimate_owner,
                                        uint32_t sub_pixel_bits) {
  std::vector<uint32_t> out;
  if (primitives.undefined || classes.empty()) return out;
  const bool multisample = scene.samples > 1;
  const double half_px = pixel_box_half_px(sub_pixel_bits, multisample);
  const ViewportRect viewport = viewport_rect(scene.effective_viewport());
  const std::vector<PrimitiveRef> refs = submission_order(primitives);
  std::vector<uint8_t> open(size_t(scene.width) * scene.height, 0);
  // Pixels a line may cover.
  for (const PrimitiveRef& ref : refs) {
    if (ref.line == nullptr) continue;
    const PixelRect r = reach(scene, ref, sub_pixel_bits, multisample);
    for (int32_t py = r.y0; py <= r.y1; ++py) {
      const IndexSpan columns = line_columns(ref.line->shape, half_px, py, r.x0, r.x1);
      for (int32_t px = columns.first; px <= columns.last; ++px) {
        const size_t pixel = size_t(py) * scene.width + size_t(px);
        if (open[pixel] == 0 && any_sample_must(classes, pixel, scene.samples) &&
            coverage_at(ref, viewport, px, py, sub_pixel_bits, multisample) != Coverage::None)
          open[pixel] = 1;
      }
    }
  }
  // Pixels whose estimated owner may not cover them: each primitive marks the samples it owns in
  // the estimate where it may cover the pixel (row spans, so the cost is the primitives' area).
  std::vector<uint8_t> explained(estimate_owner.size(), 0);
  const auto mark = [&](const PrimitiveRef& ref, int32_t px, int32_t py, bool may_known) {
    const size_t first = (size_t(py) * scene.width + size_t(px)) * scene.samples;
    bool owns = false;
    for (uint32_t s = 0; s < scene.samples; ++s) owns = owns || estimate_owner[first + s] == ref.owner;
    if (!owns) return;
    if (!may_known && coverage_at(ref, viewport, px, py, sub_pixel_bits, multisample) == Coverage::None) return;
    for (uint32_t s = 0; s < scene.samples; ++s)
      if (estimate_owner[first + s] == ref.owner) explained[first + s] = 1;
  };
  for (const PrimitiveRef& ref : refs) {
    const PixelRect r = reach(scene, ref, sub_pixel_bits, multisample);
    for (int32_t py = r.y0; py <= r.y1; ++py) {
      if (ref.triangle == nullptr) {
        const IndexSpan columns = line_columns(ref.line->shape, half_px, py, r.x0, r.x1);
        for (int32_t px = columns.first; px <= columns.last; ++px) mark(ref, px, py, false);
        continue;
      }
      const RowSpans spans = row_spans(ref.triangle->snapped, py, sub_pixel_bits, multisample);
      const int64_t first = std::max<int64_t>(spans.touch_first, r.x0),
                    last = std::min<int64_t>(spans.touch_last, r.x1);
      for (int64_t px = first; px <= last; ++px) mark(ref, int32_t(px), py, true);  // the touch span: not NONE
    }
  }
  for (size_t i = 0; i < explained.size(); ++i) {
    const size_t pixel = i / scene.samples;
    if (explained[i] == 0 && estimate_owner[i] != kOwnerBackground && classes[i] == CoverageClass::Must)
      open[pixel] = 1;
  }
  for (size_t i = 0; i < open.size(); ++i)
    if (open[i] != 0) out.push_back(uint32_t(i));
  return out;
}

std::vector<OwnerAlternative> open_owner_alternatives(const Scene& scene, const SpecPrimitives& primitives,
                                                      uint32_t sub_pixel_bits, const std::vector<uint32_t>& open_pixels,
                                                      const PixelBuffer& estimate_owner) {
  std::vector<OwnerAlternative> out;
  if (open_pixels.empty()) return out;
  const bool multisample = scene.samples > 1;
  const ViewportRect viewport = viewport_rect(scene.effective_viewport());
  const std::vector<PrimitiveRef> refs = submission_order(primitives);
  // The primitives that may reach each open pixel, in submission order.
  std::vector<std::vector<uint32_t>> reaching(open_pixels.size());
  uint64_t work = 0;
  for (uint32_t ri = 0; ri < refs.size(); ++ri) {
    const PixelRect r = reach(scene, refs[ri], sub_pixel_bits, multisample);
    if (r.x0 > r.x1) continue;
    for (int32_t py = r.y0; py <= r.y1; ++py) {
      const uint32_t row = uint32_t(py) * scene.width;
      auto it = std::lower_bound(open_pixels.begin(), open_pixels.end(), row + uint32_t(r.x0));
      for (; it != open_pixels.end() && *it <= row + uint32_t(r.x1); ++it) {
        if (++work > kOpenOwnerWorkLimit) return {};
        reaching[size_t(it - open_pixels.begin())].push_back(ri);
      }
    }
  }
  const BeatRule rule(scene);
  std::vector<Fragment> here;
  for (size_t k = 0; k < open_pixels.size(); ++k) {
    const int32_t px = int32_t(open_pixels[k] % scene.width), py = int32_t(open_pixels[k] / scene.width);
    here.clear();
    for (const uint32_t ri : reaching[k]) {
      const PrimitiveRef& ref = refs[ri];
      const Coverage coverage = coverage_at(ref, viewport, px, py, sub_pixel_bits, multisample);
      if (coverage == Coverage::None) continue;
      Fragment f;
      f.ref = &ref;
      f.certain = coverage == Coverage::Full && gate_at(ref, px, py) == Gate::Certain;
      if (scene.has_depth())
        f.interval = depth_format_interval(scene.depth_format,
                                           fragment_depth_range(ref.depth(), glm::dvec2(px + 0.5, py + 0.5)));
      here.push_back(f);
    }
    std::vector<uint32_t> allowed;
    for (const Fragment& p : here) {
      const bool beaten = std::any_of(here.begin(), here.end(), [&](const Fragment& c) {
        return c.certain && c.ref->owner != p.ref->owner && rule.certainly_beats(c, p);
      });
      if (!beaten && (allowed.empty() || allowed.back() != p.ref->owner)) allowed.push_back(p.ref->owner);
    }
    allowed.erase(std::unique(allowed.begin(), allowed.end()), allowed.end());
    for (uint32_t s = 0; s < scene.samples; ++s) {
      const size_t index = size_t(open_pixels[k]) * scene.samples + s;
      for (const uint32_t owner : allowed)
        if (owner != estimate_owner[index]) out.push_back({uint64_t(index), owner});
    }
  }
  return out;
}

std::vector<PrimitiveAtPixel> primitives_at(const Scene& scene, const SpecPrimitives& primitives,
                                            uint32_t sub_pixel_bits, int32_t px, int32_t py) {
  const bool multisample = scene.samples > 1;
  const ViewportRect viewport = viewport_rect(scene.effective_viewport());
  std::vector<PrimitiveAtPixel> out;
  for (const PrimitiveRef& ref : submission_order(primitives)) {
    const PixelRect r = reach(scene, ref, sub_pixel_bits, multisample);
    if (px < r.x0 || px > r.x1 || py < r.y0 || py > r.y1) continue;
    const Coverage coverage = coverage_at(ref, viewport, px, py, sub_pixel_bits, multisample);
    out.push_back(
        {ref.owner, ref.line != nullptr, coverage, coverage == Coverage::None ? Gate::Never : gate_at(ref, px, py)});
  }
  return out;
}

}  // namespace rastercmp::cpu::spec
