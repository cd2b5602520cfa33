// The painter's algorithm: sort polygons by depth and draw them back to front, so nearer ones
// paint over farther ones. Notes: lecture-graphics-pipeline-cyrus-beck.txt "Painter's Algorithm"
// ("Sort surfaces/polygons by their depth (z values); draw objects in order (farthest to
// closest)"); lecture-rasterization-depth-sorting-culling.txt "Painter's Algorithm", "Hard Cases".
//
// View space of the visibility methods: the viewer looks along +z, depth = z, larger z is farther.
//
// Does: a stable back-to-front order of polygon indices by one depth key per polygon.
// Does not: Newell's overlap tests or polygon splitting, so it fails on cyclic overlap and on
//       penetration (the notes' "Hard Cases"); visibility_bsp.hpp splits and gets those right.
#pragma once

#include <cstddef>
#include <vector>

#include "cpu_raster/methods/plane3.hpp"

namespace rastercmp::methods {

enum class PainterKey {
  FarthestVertex,  // the largest z of the polygon (the usual first sort of depth-sort methods)
  Centroid,        // the mean z of its vertices
};

// The depth a polygon is sorted by (the largest or the mean z of its vertices).
double painter_key(const Polygon3& polygon, PainterKey key);

// Indices into `polygons`, farthest first (larger painter_key first); ties keep input order.
std::vector<size_t> painter_order(const std::vector<Polygon3>& polygons, PainterKey key = PainterKey::FarthestVertex);

}  // namespace rastercmp::methods
