#include "cpu_raster/classic/classic_visibility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cpu_raster/methods/visibility_bsp.hpp"
#include "cpu_raster/methods/visibility_painter.hpp"
#include "model/errors.hpp"

namespace rastercmp::cpu::classic {
namespace {

constexpr methods::Vec4 kViewerAlongPlusZ{0, 0, -1, 0};  // visibility_bsp.hpp: viewer at z = -infinity

std::vector<methods::Polygon3> window_polygons(const std::vector<ClassicPrimitive>& primitives) {
  std::vector<methods::Polygon3> polygons;
  for (size_t i = 0; i < primitives.size(); ++i) {
    const ClassicPrimitive& p = primitives[i];
    if (p.is_line)
      throw NotSupportedError("visibility=painter and visibility=bsp order triangles only; the scene draws lines");
    methods::Polygon3 polygon;
    polygon.id = uint32_t(i);
    for (size_t k = 0; k < 3; ++k) polygon.vertices.push_back({p.window[k].x, p.window[k].y, p.window[k].z});
    polygons.push_back(polygon);
  }
  return polygons;
}

double distance_to_segment(methods::Vec2 p, methods::Vec2 a, methods::Vec2 b) {
  const methods::Vec2 ab = b - a;
  const double length2 = methods::dot(ab, ab);
  const double t = length2 > 0 ? std::clamp(methods::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  const methods::Vec2 q = a + ab * t - p;
  return std::sqrt(methods::dot(q, q));
}

methods::Polygon2 outline_2d(const methods::Polygon3& piece) {
  methods::Polygon2 outline;
  for (const methods::Vec3& v : piece.vertices) outline.push_back({v.x, v.y});
  return outline;
}

// The rank (position in the back-to-front order) of the piece of a triangle holding a pixel centre.
size_t piece_rank_at(const std::vector<methods::Polygon2>& outlines, const std::vector<size_t>& ranks,
                     methods::Vec2 centre) {
  size_t nearest = ranks.front();
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (size_t r : ranks) {
    const methods::Polygon2& outline = outlines[r];
    if (methods::winding_number(outline, centre) != 0) return r;
    for (size_t k = 0; k < outline.size(); ++k) {
      const double d = distance_to_segment(centre, outline[k], outline[(k + 1) % outline.size()]);
      if (d < nearest_distance) nearest_distance = d, nearest = r;
    }
  }
  return nearest;
}

struct RankedFragment {
  size_t rank = 0;
  PaintedFragment painted;
};

std::vector<PaintedFragment> in_rank_order(std::vector<RankedFragment>& ranked) {
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const RankedFragment& a, const RankedFragment& b) { return a.rank < b.rank; });
  std::vector<PaintedFragment> ordered;
  ordered.reserve(ranked.size());
  for (const RankedFragment& r : ranked) ordered.push_back(r.painted);
  return ordered;
}

std::vector<PaintedFragment> painter_fragments(const std::vector<ClassicPrimitive>& primitives,
                                               const ClassicMethods& chosen, const PixelRect& region) {
  std::vector<PaintedFragment> ordered;
  for (size_t i : methods::painter_order(window_polygons(primitives), methods::PainterKey::FarthestVertex))
    for_each_fragment(primitives[i], chosen, region, [&](const Fragment& f) { ordered.push_back({f, i}); });
  return ordered;
}

std::vector<PaintedFragment> bsp_fragments(const std::vector<ClassicPrimitive>& primitives,
                                           const ClassicMethods& chosen, const PixelRect& region) {
  const std::vector<methods::Polygon3> order =
      methods::bsp_back_to_front(methods::build_bsp(window_polygons(primitives)), kViewerAlongPlusZ);
  std::vector<methods::Polygon2> outlines;
  std::vector<std::vector<size_t>> ranks_of(primitives.size());
  for (size_t r = 0; r < order.size(); ++r) {
    outlines.push_back(outline_2d(order[r]));
    ranks_of[order[r].id].push_back(r);
  }
  std::vector<RankedFragment> ranked;
  for (size_t i = 0; i < primitives.size(); ++i) {
    if (ranks_of[i].empty()) continue;  // no area in window space: build_bsp dropped it
    for_each_fragment(primitives[i], chosen, region, [&](const Fragment& f) {
      ranked.push_back({piece_rank_at(outlines, ranks_of[i], {f.x + 0.5, f.y + 0.5}), {f, i}});
    });
  }
  return in_rank_order(ranked);
}

}  // namespace

std::vector<PaintedFragment> back_to_front_fragments(const std::vector<ClassicPrimitive>& primitives,
                                                     const ClassicMethods& chosen, const PixelRect& region) {
  return chosen.visibility == VisibilityMethod::Bsp ? bsp_fragments(primitives, chosen, region)
                                                    : painter_fragments(primitives, chosen, region);
}

}  // namespace rastercmp::cpu::classic
