// Scenes of the method maps (experiments/method_maps.hpp): each one puts a method family where the
// lecture notes say it breaks, one parameter at a time. Window-space scenes go through
// pixels_to_clip (w = 1, z is the window depth), so a parameter is a distance in pixels or
// sub-pixels (1/256 pixel, the 24.8 grid of docs/lavapipe-rules.md §2.1).
#pragma once

#include "model/scene.hpp"

namespace rastercmp::experiments {

// fill: a sliver 56 pixels long, `width_subpx` sub-pixels wide at its wide end (x = 4), where the
// pixel centres of row 10 lie 0.3 of the width above its lower edge; that edge rises by half the
// width to the apex, so row 10 leaves the sliver near x = 37.6, at a point that moves with every
// rounding of the vertices (notes CFZ "Polygon Filling": slivers lose or gain spans).
Scene make_sliver_strip(double width_subpx);

// fill: a fan of 8 triangles around a shared vertex at pixel centre (16.5, 16.5) moved by
// `offset_subpx` sub-pixels along x and y (0 = on a sample position; a non-integer offset is off the
// 24.8 grid), outer vertices on a radius-12 circle (notes RDS "Rasterizing a Triangle": shared edges).
Scene make_fan(double offset_subpx);

// visibility: three bars around the frame centre, each crossing the other two, at mean window
// depths 0.4, 0.5, 0.6 and tilted along their length by +-`tilt`. Each bar meets the next one at
// +-kCyclicCrossing of its half-length, so the overlap is cyclic once tilt * kCyclicCrossing > 0.05
// (notes RDS "Painter's Algorithm", "Hard Cases"; GPC "Painter's Algorithm").
Scene make_cyclic_bars(double tilt);
double cyclic_bars_onset_tilt();  // 0.05 / crossing parameter: the tilt at which the cycle closes

// visibility: a square at window depth 0.5 and a second square behind it, tilted along x, whose near
// edge reaches depth 0.55 - `penetration`: the two interpenetrate once penetration > 0.05.
Scene make_interpenetration(double penetration);
inline constexpr double kInterpenetrationOnset = 0.05;

// clip: a line from inside the frame to a vertex on the near plane (z = 0) with clip w = `w`.
Scene make_near_w_line(float w);

// clip: a triangle (or a line) with one vertex `behind` clip units behind the near plane (z = -behind,
// w = 1), so the near plane cuts it.
Scene make_near_cross_triangle(double behind);
Scene make_near_cross_line(double behind);

// depth: a scene of a camera with these planes (model/camera.hpp, Vulkan's 0..1 depth), with reversed
// Z: every clip z replaced by w - z = near (far - w) / (far - near), computed from w, so near maps to
// 1 and far to 0 (the float format's dense end at the far plane); compare op Greater, depth cleared to 0.
Scene reversed_z(Scene scene, double near_plane, double far_plane);

}  // namespace rastercmp::experiments
