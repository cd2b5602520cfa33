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

namespace rastercmp::cpu::classic {

struct PaintedFragment {
  Fragment fragment;
  size_t primitive = 0;  // index into the primitives
};

// All fragments in painting order. Throws NotSupportedError for line primitives.
std::vector<PaintedFragment> back_to_front_fragments(const std::vector<ClassicPrimitive>& primitives,
                                                     const ClassicMethods& chosen, const PixelRect& region);

}  // namespace rastercmp::cpu::classic
