// Sutherland–Hodgman polygon clipping: the subject polygon is clipped against one boundary at a
// time ("Pipeline Clipping of Polygons", lecture-rasterization-depth-sorting-culling.txt;
// "Sutherland-Hodgman (poly vs convex poly)", lecture-depth-clipping-polygon-offset.txt).
//
// Does: 2D against a convex polygon window (either orientation) or a rectangle; 3D against a box
//       or the homogeneous clip volume (clip_volume.hpp planes, in that order), before the divide.
//       Per boundary and per subject edge s -> e: in->in emits e, in->out emits the crossing,
//       out->in emits the crossing then e, out->out emits nothing. Points on a boundary are in.
// Does not: split a concave subject into pieces — where the clipped region falls apart, the output
//       is one polygon joined by zero-area edges along the window boundary (its signed area is
//       still the area of the intersection); use clip_polygon_weiler_atherton.hpp for separate
//       pieces. Does not remove repeated vertices. Returns an empty polygon when nothing is left.
#pragma once

#include <vector>

#include "cpu_raster/methods/clip_volume.hpp"
#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

// Throws std::invalid_argument if the window is not convex with non-zero area.
Polygon2 clip_polygon_sutherland_hodgman(const Polygon2& subject, const Polygon2& convex_window);
Polygon2 clip_polygon_sutherland_hodgman(const Polygon2& subject, const Rect2& window);

// Clip-space polygon (before the perspective divide) against the six planes of `volume`.
std::vector<Vec4> clip_polygon_sutherland_hodgman(const std::vector<Vec4>& subject_clip, const ClipVolume& volume);

}  // namespace rastercmp::methods
