// Triangle clipping, draw_pipe_clip.c clip_tri / do_clip_tri (docs/lavapipe-rules.md §1.5, §1.6; steps 6, 7).
// Sutherland–Hodgman over the planes of the union of the vertex masks, in increasing bit order;
// each new vertex starts from the vertex nearer the plane; a non-finite plane distance drops the
// whole primitive; the polygon is fanned as (p0, p[k-1], p[k]) (provoking vertex first).
// Not modelled: user clip planes, clip distances, the guard band (never used with our targets).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cpu_raster/exact/clip_vertex.hpp"

namespace rastercmp::cpu {

enum class ClipFate {
  Inside,     // OR of the masks is 0: passed unchanged
  Clipped,    // the polygon was cut; `triangles` holds the fan (possibly empty)
  Outside,    // AND of the masks is non-zero: trivially rejected
  Discarded,  // an Inf/NaN plane distance, or more vertices than the clipper holds
};

struct ClippedTriangles {
  ClipFate fate = ClipFate::Inside;
  std::vector<std::array<ClipVertex, 3>> triangles;  // what goes on to set-up, in emit order
};

// `inside_planes`: planes to clip a triangle wholly inside against anyway (WorkSkips::
// clip_only_when_needed off; 0: pass it unchanged, as lavapipe does). Every plane distance of such
// a triangle is >= 0, so the clipper returns it unchanged (fate stays Inside). A non-finite distance,
// which the clip test lets through (w = +Inf; |x| + w overflowing; z Inf or NaN without depth
// clipping), would make do_clip_tri discard it although lavapipe never clips it: it is then passed
// unchanged too. Forcing the clipper does not make a draw "pipelined" (§2.6's float cull).
ClippedTriangles clip_triangle(const std::array<ClipVertex, 3>& triangle, const ViewportTransform& viewport,
                               uint32_t inside_planes = 0);

}  // namespace rastercmp::cpu
