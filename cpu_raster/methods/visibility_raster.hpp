// Painting 3D polygons into an owner image, in a given order (what the painter's algorithm and
// the BSP traversal produce) or with a z-buffer (the reference both are judged against).
// Notes: notes-line-clipping-hidden-surface.txt "The Z-Buffer Algorithm" (start every pixel at
// the background distance; draw a point only if its distance is less than the stored one);
// lecture-graphics-pipeline-cyrus-beck.txt "Z-buffer Algorithm".
//
// View space as in visibility_painter.hpp: orthographic along +z, depth = z (larger is farther),
// one view-space unit per pixel, pixel (x, y) sampled at (x + 0.5, y + 0.5). Coverage is the
// non-zero rule of fill_polygon_rule.hpp (half-open edges: pieces of a split polygon cover every
// pixel exactly once); depth is the polygon's plane at the sample point, in double.
//
// Does: owner ids per pixel (kNoOwner where nothing was drawn), with the depth buffer for the
//       z-buffer form. Does not: perspective, shading, depth formats (the pipeline's business).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "cpu_raster/methods/plane3.hpp"

namespace rastercmp::methods {

inline constexpr uint32_t kNoOwner = std::numeric_limits<uint32_t>::max();

struct OwnerImage {
  int32_t width = 0, height = 0;
  std::vector<uint32_t> owner;  // index y * width + x
  std::vector<double> depth;    // z-buffer form only: the stored distance (+inf: background)

  uint32_t at(int32_t x, int32_t y) const { return owner[size_t(y) * size_t(width) + size_t(x)]; }
};

// Later polygons overwrite earlier ones wherever they cover a pixel (no depth test).
OwnerImage paint_in_order(const std::vector<Polygon3>& polygons_back_to_front, int32_t width, int32_t height);

// A pixel takes a polygon's id when its depth there is strictly less than the stored one.
OwnerImage paint_with_zbuffer(const std::vector<Polygon3>& polygons, int32_t width, int32_t height);

}  // namespace rastercmp::methods
