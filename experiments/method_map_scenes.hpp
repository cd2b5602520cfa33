// Scenes of the method maps (experiments/method_maps.hpp): each one puts a method family where the
// lecture notes say it breaks, one parameter at a time. Window-space scenes go through
// pixels_to_clip (w = 1, z is the window depth), so a parameter is a distance in pixels or
// sub-pixels (1/256 pixel, the 24.8 grid of docs/lavapipe-rules.md §2.1).
#pragma once

#include <utility>

#include <glm/vec2.hpp>

#include "experiments/coverage_model.hpp"
#include "model/scene.hpp"

namespace rastercmp::experiments {

// fill: a sliver 56 pixels long, `width_subpx` sub-pixels wide at its wide end (x = 4), where the
// pixel centres of row 10 lie 0.3 of the width above its lower edge; that edge rises by half the
// width to the apex, so row 10 leaves the sliver near x = 37.6, at a point that moves with every
// rounding of the vertices (notes CFZ "Polygon Filling": slivers lose or gain spans).
Scene make_sliver_strip(double width_subpx);
DesignTriangles sliver_strip_design(double width_subpx);  // its triangle, for the coverage model

// fill: a fan of 8 triangles around a shared vertex at pixel centre (16.5, 16.5) moved by
// `offset_subpx` sub-pixels along x and y (0 = on a sample position; a non-integer offset is off the
// 24.8 grid), outer vertices on a radius-12 circle (notes RDS "Rasterizing a Triangle": shared edges).
Scene make_fan(double offset_subpx);
DesignTriangles fan_design(double offset_subpx);

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

// line: a 1-pixel line of `mode` (docs/lavapipe-rules.md §4) from window (8.5, 8.5), a pixel centre, in a
// frame wide enough for the longest line (272 x 96), drawn with depth test off.
//   slope:      40 pixels long at `angle_deg` (0 = along +x, 90 = along +y), its end rounded to the
//               nearest pixel centre, so both ends are integer pixels at centres at every slope
//   end_offset: to the pixel centre (49.5, 21.5) (41 x 13 pixels, no exact half on any column)
//               with the end moved by `offset_px` along +y (across the line), off its centre
//   length:     `length_px` pixels along x and round(length / 3) along y (ends at centres)
Scene make_line_slope(LineMode mode, double angle_deg);
Scene make_line_end_offset(LineMode mode, double offset_px);
Scene make_line_length(LineMode mode, double length_px);
glm::dvec2 line_slope_run(double angle_deg);    // the slope line's far end minus its start, whole pixels
glm::dvec2 line_length_run(double length_px);   // the same for the length line
inline constexpr int kLineOffsetRun = 41, kLineOffsetRise = 13;  // end_offset's line, in pixels

// cull: one triangle seen through a 60-degree perspective camera (near 0.5, far 100, Vulkan's 0..1
// clip z), back faces culled, counter-clockwise front. Its normal is tilted by `angle_deg` from the
// view axis (0: facing the eye, 90: along the axis) about the y axis. Cases (CullPlace):
//   on_axis      centre on the view axis 4 units away (about 42 pixels across face-on)
//   off_axis     centre kCullOffAxisDeg off the axis: the face is edge-on to the eye's ray at
//                angle_deg = 90 - kCullOffAxisDeg, where a view-along-the-axis test would say 90
//   y_flip       on_axis through a viewport of negative height (window y up)
//   near_clipped centre 1.5 units away, half-size 2.5: near edge-on one vertex lies behind the near
//                plane (and behind the eye), so the exact path clips it first
enum class CullPlace { OnAxis, OffAxis, YFlip, NearClipped };
Scene make_cull_face(CullPlace place, double angle_deg);
inline constexpr std::pair<const char*, CullPlace> kCullPlaces[] = {{"on_axis", CullPlace::OnAxis},
                                                                    {"off_axis", CullPlace::OffAxis},
                                                                    {"y_flip", CullPlace::YFlip},
                                                                    {"near_clipped", CullPlace::NearClipped}};
inline constexpr double kCullOffAxisDeg = 5;
// The angle of the face's normal to the view axis at which it is edge-on to the eye's ray through
// its centre (N . V = 0 at the centre): 90 - kCullOffAxisDeg off the axis, 90 elsewhere.
double cull_edge_on_deg(CullPlace place);
// The face's size across, in pixels, seen face-on (on_axis): the snapping band's scale.
double cull_face_pixels();

// depth: a scene of a camera with these planes (model/camera.hpp, Vulkan's 0..1 depth), with reversed
// Z: every clip z replaced by w - z = near (far - w) / (far - near), computed from w, so near maps to
// 1 and far to 0 (the float format's dense end at the far plane); compare op Greater, depth cleared to 0.
Scene reversed_z(Scene scene, double near_plane, double far_plane);

}  // namespace rastercmp::experiments
