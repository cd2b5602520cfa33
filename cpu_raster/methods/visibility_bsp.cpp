#include "cpu_raster/methods/visibility_bsp.hpp"

namespace rastercmp::methods {

namespace {

bool has_area(const Polygon3& polygon) {
  const Vec3 n = newell_normal(polygon.vertices);
  return polygon.vertices.size() >= 3 && (n.x != 0 || n.y != 0 || n.z != 0);
}

// SkapaBSP: returns the node index of the subtree of `polygons` (-1 for none).
int32_t build_node(BspTree& tree, std::vector<Polygon3> polygons, double epsilon) {
  if (polygons.empty()) return -1;
  BspNode node;
  node.plane = plane_of(polygons[0]);
  node.polygons.push_back(polygons[0]);
  std::vector<Polygon3> behind, in_front;
  for (size_t i = 1; i < polygons.size(); ++i) {
    switch (classify(polygons[i], node.plane, epsilon)) {
      case PlaneSide::Coplanar: node.polygons.push_back(polygons[i]); break;
      case PlaneSide::Back: behind.push_back(polygons[i]); break;
      case PlaneSide::Front: in_front.push_back(polygons[i]); break;
      case PlaneSide::Spanning: {
        SplitPolygon pieces = split(polygons[i], node.plane, epsilon);
        ++tree.splits;
        if (has_area(pieces.back)) behind.push_back(std::move(pieces.back));
        if (has_area(pieces.front)) in_front.push_back(std::move(pieces.front));
        break;
      }
    }
  }
  const int32_t index = int32_t(tree.nodes.size());
  tree.nodes.push_back(std::move(node));
  const int32_t behind_index = build_node(tree, std::move(behind), epsilon);
  const int32_t in_front_index = build_node(tree, std::move(in_front), epsilon);
  tree.nodes[size_t(index)].behind = behind_index;
  tree.nodes[size_t(index)].in_front = in_front_index;
  return index;
}

// RitaBSP.
void draw_node(const BspTree& tree, int32_t index, Vec4 viewer, std::vector<int32_t>& out) {
  if (index < 0) return;
  const BspNode& node = tree.nodes[size_t(index)];
  const bool viewer_in_front = viewer_side(node.plane, viewer) > 0;
  draw_node(tree, viewer_in_front ? node.behind : node.in_front, viewer, out);
  out.push_back(index);
  draw_node(tree, viewer_in_front ? node.in_front : node.behind, viewer, out);
}

}  // namespace

BspTree build_bsp(const std::vector<Polygon3>& polygons, double epsilon) {
  BspTree tree;
  std::vector<Polygon3> usable;
  for (const Polygon3& p : polygons) {
    if (has_area(p)) usable.push_back(p);
  }
  tree.root = build_node(tree, std::move(usable), epsilon);
  return tree;
}

std::vector<int32_t> bsp_node_order(const BspTree& tree, Vec4 viewer) {
  std::vector<int32_t> order;
  order.reserve(tree.nodes.size());
  draw_node(tree, tree.root, viewer, order);
  return order;
}

std::vector<Polygon3> bsp_back_to_front(const BspTree& tree, Vec4 viewer) {
  std::vector<Polygon3> out;
  for (int32_t index : bsp_node_order(tree, viewer)) {
    const BspNode& node = tree.nodes[size_t(index)];
    out.insert(out.end(), node.polygons.begin(), node.polygons.end());
  }
  return out;
}

}  // namespace rastercmp::methods
