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

// The tree of the window-space triangles and its back-to-front order for the viewer: the pieces'
// outlines by rank, each primitive's ranks and each rank's node.
struct BspOrder {
  methods::BspTree tree;
  std::vector<methods::Polygon2> outlines;
  std::vector<std::vector<size_t>> ranks_of;
  std::vector<int32_t> node_of_rank;
};

BspOrder bsp_order(const std::vector<ClassicPrimitive>& primitives) {
  BspOrder order{
      methods::build_bsp(window_polygons(primitives)), {}, std::vector<std::vector<size_t>>(primitives.size()), {}};
  // methods::bsp_back_to_front's order: the nodes' polygons in bsp_node_order.
  for (int32_t node : methods::bsp_node_order(order.tree, kViewerAlongPlusZ))
    for (const methods::Polygon3& piece : order.tree.nodes[size_t(node)].polygons) {
      order.ranks_of[piece.id].push_back(order.outlines.size());
      order.outlines.push_back(outline_2d(piece));
      order.node_of_rank.push_back(node);
    }
  return order;
}

std::vector<PaintedFragment> bsp_fragments(const std::vector<ClassicPrimitive>& primitives,
                                           const ClassicMethods& chosen, const PixelRect& region) {
  const BspOrder order = bsp_order(primitives);
  std::vector<RankedFragment> ranked;
  for (size_t i = 0; i < primitives.size(); ++i) {
    if (order.ranks_of[i].empty()) continue;  // no area in window space: build_bsp dropped it
    for_each_fragment(primitives[i], chosen, region, [&](const Fragment& f) {
      ranked.push_back({piece_rank_at(order.outlines, order.ranks_of[i], {f.x + 0.5, f.y + 0.5}), {f, i}});
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

std::vector<PainterKeyed> painter_keys(const std::vector<ClassicPrimitive>& primitives) {
  const std::vector<methods::Polygon3> polygons = window_polygons(primitives);
  std::vector<PainterKeyed> keyed;
  for (size_t i : methods::painter_order(polygons, methods::PainterKey::FarthestVertex))
    keyed.push_back({i, methods::painter_key(polygons[i], methods::PainterKey::FarthestVertex)});
  return keyed;
}

BspPixelTrace bsp_pixel_trace(const std::vector<ClassicPrimitive>& primitives, const std::vector<size_t>& at_pixel,
                              int32_t x, int32_t y) {
  const BspOrder order = bsp_order(primitives);
  BspPixelTrace trace;
  trace.nodes = order.tree.nodes.size();
  trace.splits = order.tree.splits;
  trace.polygons = order.outlines.size();
  // Each node's parent and the side of it the node hangs on.
  std::vector<std::pair<int32_t, int>> parent(order.tree.nodes.size(), {-1, 0});
  for (size_t n = 0; n < order.tree.nodes.size(); ++n) {
    const methods::BspNode& node = order.tree.nodes[n];
    if (node.behind >= 0) parent[size_t(node.behind)] = {int32_t(n), -1};
    if (node.in_front >= 0) parent[size_t(node.in_front)] = {int32_t(n), +1};
  }
  const auto test_at = [&](int32_t n, int path) {
    const methods::BspNode& node = order.tree.nodes[size_t(n)];
    return BspNodeTest{n, node.polygons.front().id, node.plane, methods::viewer_side(node.plane, kViewerAlongPlusZ),
                       path};
  };
  for (size_t i : at_pixel) {
    BspPieceTrace piece;
    piece.primitive = i;
    piece.pieces = order.ranks_of[i].size();
    if (order.ranks_of[i].empty()) {  // no area in window space: not in the tree
      trace.pieces.push_back(piece);
      continue;
    }
    piece.rank = piece_rank_at(order.outlines, order.ranks_of[i], {x + 0.5, y + 0.5});
    int32_t node = order.node_of_rank[piece.rank];
    piece.path.push_back(test_at(node, 0));
    for (auto up = parent[size_t(node)]; up.first >= 0; up = parent[size_t(up.first)])
      piece.path.insert(piece.path.begin(), test_at(up.first, up.second));
    trace.pieces.push_back(piece);
  }
  return trace;
}

}  // namespace rastercmp::cpu::classic
