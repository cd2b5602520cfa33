// The clip stage of the classic path, in clip space before the divide (docs/methods.md
// "Selecting a method"). Each clipper returns clip-space vertices with their window coordinates:
// a vertex the clipper kept is the original ClipVertex (the JIT viewport transform, as the exact
// path), a vertex it made gets the C viewport transform (docs/lavapipe-rules.md §1.6), as lavapipe's
// clipper's new vertices do.
//  - triangles, sutherland_hodgman: methods::clip_polygon_sutherland_hodgman against the Vulkan
//    volume -w <= x, y <= w, 0 <= z <= w (z planes only with depth clip on), fanned (p0, pk-1, pk);
//  - lines, cohen_sutherland_3d: methods::clip_line_cohen_sutherland_3d with 6-bit outcodes;
//  - triangles, weiler_atherton; lines, cohen_sutherland and cyrus_beck: 2-D, below;
//  - lines, liang_barsky: the parametric clipper of methods/clip_line_liang_barsky.hpp carried
//    to the six homogeneous planes (t = d0 / (d0 - d1) per plane, one pass).
// As in the exact clipper, a primitive whose vertices are all inside passes unchanged, one outside
// a common plane is rejected, and one with a non-finite coordinate is dropped.
#pragma once

#include <array>
#include <vector>

#include "cpu_raster/exact/clip_vertex.hpp"

namespace rastercmp::cpu::classic {

std::vector<std::array<ClipVertex, 3>> clip_triangle_sutherland_hodgman(const std::array<ClipVertex, 3>& triangle,
                                                                        const ViewportTransform& viewport,
                                                                        bool depth_clip);

// Weiler–Atherton in window space: the triangle against the viewport rectangle as a polygon,
// each piece fanned (p0, pk-1, pk) in the triangle's own orientation; new vertices get their clip
// position from window-space barycentrics (perspective-correct). Throws NotSupportedError for a
// vertex behind the eye or outside the depth clip planes, and for degenerate contact.
std::vector<std::array<ClipVertex, 3>> clip_triangle_weiler_atherton(const std::array<ClipVertex, 3>& triangle,
                                                                     const ViewportTransform& viewport,
                                                                     bool depth_clip);

// CohenSutherland and CyrusBeck clip the window-space segment against the viewport rectangle
// (2-D, after the divide; NotSupportedError as Weiler–Atherton); the others in clip space.
enum class LineClipper { CohenSutherland3d, LiangBarsky, CohenSutherland, CyrusBeck };

struct ClassicClippedLine {
  bool visible = false;
  std::array<ClipVertex, 2> line{};
  int passes = 0;  // outcode evaluations (Cohen–Sutherland) or 1 (Liang–Barsky); 0: trivially decided
  int clips = 0;   // endpoints replaced
};

ClassicClippedLine clip_line_classic(const std::array<ClipVertex, 2>& line, const ViewportTransform& viewport,
                                     bool depth_clip, LineClipper clipper);

}  // namespace rastercmp::cpu::classic
