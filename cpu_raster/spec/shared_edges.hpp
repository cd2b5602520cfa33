// Shared-edge promotion, the CTS verifier's "sharedEdge" friends (docs/spec-profile.md).
// Vulkan "Basic Polygon Rasterization": "if two polygons lie on either side of a common edge (with
// identical endpoints) on which a sample point lies, then exactly one of the polygons must result
// in a covered sample". A sample that is PARTIAL for both triangles of such a pair, and whose box
// lies strictly inside both triangles' other two edges (every rounding variant), is therefore
// covered by one of them, whichever side of the common edge the device's snapped edge puts it on.
//
// Which edges are common: identical float window endpoints in the exact path (reversed or not), the
// two triangles on opposite sides with certain facing, and endpoints every device computes alike:
//  - two pieces of one clipped primitive (the fan's inner edges: whatever a device's clipper and
//    triangulation, the pieces tile the same convex polygon), or
//  - primitives whose unclipped triangles share an edge with identical clip-space vertices (the
//    CTS fill-rule cases clipped_full / clipped_partly require clipped shared edges to stay
//    watertight).
#pragma once

#include <cstddef>
#include <vector>

#include "cpu_raster/spec/spec_primitives.hpp"

namespace rastercmp::cpu::spec {

struct SharedEdge {
  size_t first = 0, second = 0;         // indices into the triangle list
  int first_edge = 0, second_edge = 0;  // edge i runs from vertex i to vertex (i+1)%3
};

// Pairs between triangles whose facing is certain and not culled. The caller also needs both
// triangles' depth gates Certain at the sample.
std::vector<SharedEdge> find_shared_edges(const std::vector<SpecTriangle>& triangles);

// The box lies strictly inside both triangles' edges other than the shared one.
bool promoted(const std::vector<SpecTriangle>& triangles, const SharedEdge& shared, const ToleranceBox& box);

}  // namespace rastercmp::cpu::spec
