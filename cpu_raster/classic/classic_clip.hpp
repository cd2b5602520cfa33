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
#include "cpu_raster/methods/clip_line_cohen_sutherland.hpp"
#include "cpu_raster/methods/clip_line_cohen_sutherland_3d.hpp"
#include "cpu_raster/methods/clip_line_cyrus_beck.hpp"
#include "cpu_raster/methods/clip_volume.hpp"

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

// Liang–Barsky on one homogeneous plane: the signed distances of the ends (>= 0 inside) and the
// crossing t = d0 / (d0 - d1) when one end is outside.
struct LiangBarskyPlane {
  methods::ClipPlane plane = methods::ClipPlane::XLow;
  double d0 = 0, d1 = 0;
  double t = 0;           // meaningful when entering or leaving
  bool entering = false;  // d0 < 0: raises t_in
  bool leaving = false;   // d1 < 0: lowers t_out
};

// What the line clipper decided on, for explain: the 6-bit clip-space outcodes of the ends before
// clipping (clip_volume.hpp: 1 x low, 2 x high, 4 y low, 8 y high, 16 z low, 32 z high) and the
// clipper's own variables.
struct LineClipTrace {
  uint8_t code_p0 = 0, code_p1 = 0;
  bool trivial = true;         // decided by the outcodes (OR == 0 accept, AND != 0 reject) or a non-finite end
  double t_in = 0, t_out = 1;  // Liang–Barsky (clip space) and Cyrus–Beck (window space)
  std::vector<LiangBarskyPlane> liang_barsky;             // the planes examined, in order
  std::vector<methods::CohenSutherland3dPass> passes_3d;  // cohen_sutherland_3d
  std::vector<methods::CohenSutherlandPass> passes_2d;    // cohen_sutherland, 4-bit Notes layout (window y)
  std::vector<methods::CyrusBeckStep> cyrus_beck;         // one row per viewport edge
  methods::Rect2 window{};                                // the 2-D clippers' viewport rectangle
};

struct ClassicClippedLine {
  bool visible = false;
  std::array<ClipVertex, 2> line{};
  int passes = 0;  // outcode evaluations (Cohen–Sutherland) or 1 (Liang–Barsky); 0: trivially decided
  int clips = 0;   // endpoints replaced
  LineClipTrace trace;
};

// The 6-bit outcode of a vertex against Vulkan's clip volume (z planes only with depth clip).
uint8_t clip_space_outcode(const ClipVertex& vertex, bool depth_clip);

ClassicClippedLine clip_line_classic(const std::array<ClipVertex, 2>& line, const ViewportTransform& viewport,
                                     bool depth_clip, LineClipper clipper);

}  // namespace rastercmp::cpu::classic
