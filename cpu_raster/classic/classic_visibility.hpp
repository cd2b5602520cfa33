// The visibility stages "painter" and "bsp" of the classic path: instead of the depth test, the
// fragments of all triangles of the frame are painted back to front and a later fragment always
// overwrites (docs/methods.md "Selecting a method"). Window space is the view space: x, y in
// pixels, z the window depth, the viewer looking along +z from z = -infinity, so larger z is
// farther (compare op less; other compare ops are not looked at).
//  painter  methods::painter_order of the window-space triangles (farthest vertex first), each
//           triangle painted whole;
//  bsp      methods::build_bsp of the window-space triangles (split where they cross a partition
//           plane), traversed back to front for the viewer (0, 0, -1, 0). Each fragment of a
//           triangle is painted with the piece whose outline holds the pixel centre (non-zero
//           winding; a pixel the fill covers outside every piece, at the triangle's border, takes
//           the nearest piece), so coverage is the fill's and only the order comes from the tree.
// Depth is written (when the draw writes depth) with the fragment's value, untested.
#pragma once

#include <cstdint>
#include <vector>

#include "cpu_raster/classic/classic_fragments.hpp"
#include "cpu_raster/methods/plane3.hpp"

namespace rastercmp::cpu::classic {

struct PaintedFragment {
  Fragment fragment;
  size_t primitive = 0;  // index into the primitives
};

// All fragments in painting order. Throws NotSupportedError for line primitives.
std::vector<PaintedFragment> back_to_front_fragments(const std::vector<ClassicPrimitive>& primitives,
                                                     const ClassicMethods& chosen, const PixelRect& region);

// visibility=painter's decision variables: every triangle's sort key (methods::painter_key,
// farthest vertex: its largest window z), in painting order.
struct PainterKeyed {
  size_t primitive = 0;  // index into the primitives
  double key = 0;
};
std::vector<PainterKeyed> painter_keys(const std::vector<ClassicPrimitive>& primitives);

// visibility=bsp's decision variables for the pieces that paint one pixel centre: for each given
// primitive, the piece of it holding the centre (as back_to_front_fragments picks it), its rank in
// the back-to-front order, and the path from the root to its node with the plane side test at
// each node: which side of the node's plane the viewer (0, 0, -1, 0) is, so which subtree is
// drawn first.
struct BspNodeTest {
  int32_t node = 0;
  size_t partition = 0;    // the primitive whose piece is the node's first polygon (its plane)
  methods::Plane3 plane;   // n.p + d = 0 in window space (x, y in pixels, z window depth)
  double viewer_side = 0;  // methods::viewer_side: > 0 the viewer is in front, so behind is drawn first
  int path = 0;            // where the piece goes from here: -1 behind, +1 in front, 0 this node
};
struct BspPieceTrace {
  size_t primitive = 0;
  size_t rank = 0;    // position of the piece in the back-to-front order (0 first)
  size_t pieces = 0;  // how many pieces the primitive is in the tree
  std::vector<BspNodeTest> path;
};
struct BspPixelTrace {
  size_t nodes = 0, splits = 0, polygons = 0;  // the tree; polygons: pieces in the order
  std::vector<BspPieceTrace> pieces;           // in the order of `at_pixel`
};
BspPixelTrace bsp_pixel_trace(const std::vector<ClassicPrimitive>& primitives, const std::vector<size_t>& at_pixel,
                              int32_t x, int32_t y);

}  // namespace rastercmp::cpu::classic
