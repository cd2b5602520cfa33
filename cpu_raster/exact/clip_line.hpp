// Line clipping, draw_pipe_clip.c clip_line / do_clip_line (docs/lavapipe-rules.md §1.6).
// t0/t1 accumulate max(t, dp/(dp - dp_other)) over the planes of the union mask; the line is
// dropped when t0 + t1 >= 1 or a plane distance is Inf/NaN; an endpoint with a non-zero mask is
// replaced by interp(t, endpoint, other) even when t is 0 (so it gets C window coordinates).
#pragma once

#include <array>

#include "cpu_raster/exact/clip_triangle.hpp"

namespace rastercmp::cpu {

struct ClippedLine {
  ClipFate fate = ClipFate::Inside;
  std::array<ClipVertex, 2> line{};  // valid for Inside and Clipped
  float t0 = 0, t1 = 0;              // the clip parameters of line[0] and line[1] (0: not moved)
};

// How lines meet the x and y planes (lavapipe-rules §8.2): clipped like every plane (Mesa 22.3), or
// with Mesa 23.2's clip_line_guard_xy: a line outside only in x or y is drawn whole (dropped when
// both w <= 0 or an x or y is NaN), the draw region cutting it in set-up; one outside a depth plane
// too is clipped against the depth planes alone, unless both endpoints share an outside bit.
enum class LineXyClip { Clip, GuardBand };

// `inside_planes`: as for clip_triangle, planes to run a line wholly inside through anyway; it comes
// back unchanged (t0 = t1 = 0; no endpoint has a mask bit, so none is replaced).
ClippedLine clip_line(const std::array<ClipVertex, 2>& line, const ViewportTransform& viewport,
                      uint32_t inside_planes = 0, LineXyClip xy = LineXyClip::Clip);

}  // namespace rastercmp::cpu
