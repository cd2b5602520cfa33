// Polygon-aligned BSP tree: built once, with polygons that cross a partition plane split in two,
// then traversed back to front for any viewer. Notes: lecture-rasterization-depth-sorting-
// culling.txt "Polygon-aligned BSP tree" and "Algorithm for BSP trees" (SkapaBSP: pick a polygon
// P, list B the polygons behind P, H the others, recurse; RitaBSP: if the viewer is in front of
// the root draw behind, root, front, else front, root, behind).
//
// Does: the root of each subtree is the first polygon of its list (the notes' "Välj en polygon
//       P"); polygons coplanar with it are kept at its node; spanning ones are split (the pieces
//       keep their id). Traversal takes a homogeneous viewer: (x, y, z, 1) an eye point, or
//       (x, y, z, 0) a direction towards a viewer at infinity (orthographic view), e.g.
//       (0, 0, -1, 0) for the view space of visibility_painter.hpp.
// Does not: choose partition planes to balance the tree or limit splits, or cull (a polygon
//       facing away is still drawn; see cull_back_face.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "cpu_raster/methods/plane3.hpp"

namespace rastercmp::methods {

struct BspNode {
  Plane3 plane;
  std::vector<Polygon3> polygons;      // the partition polygon first, then those coplanar with it
  int32_t behind = -1, in_front = -1;  // child node indices; -1: empty subtree
};

struct BspTree {
  std::vector<BspNode> nodes;
  int32_t root = -1;
  size_t splits = 0;  // polygons split while building
};

// Polygons with no area are dropped. `epsilon`: distance (in world units) within which a vertex
// counts as on a partition plane.
BspTree build_bsp(const std::vector<Polygon3>& polygons, double epsilon = 1e-9);

// The nodes in RitaBSP's drawing order for `viewer`: at each node the subtree on the far side of its
// plane (viewer_side > 0: behind), then the node's polygons, then the near side.
std::vector<int32_t> bsp_node_order(const BspTree& tree, Vec4 viewer);

// All polygons (split pieces included) in back-to-front order for `viewer`: the polygons of the
// nodes of bsp_node_order, each node's in its own order.
std::vector<Polygon3> bsp_back_to_front(const BspTree& tree, Vec4 viewer);

}  // namespace rastercmp::methods
