// Textbook bilinear depth interpolation: along two edges to the scanline, then across the span.
// Notes: lecture-depth-clipping-polygon-offset.txt "Bilinear interpolation" and its worked
// example ("Interpolation - Y", "Interpolation - X"); lecture-clipping-fill-zbuffer.txt
// "Interpolate Z-value" ("first interpolate up the sides and then to interpolate across").
//
//   f(R1) = (y - y1)/(y2 - y1) f(Q2) + (y2 - y)/(y2 - y1) f(Q1)     (edge Q1 -> Q2 at height y)
//   f(P)  = (x - x1)/(x2 - x1) f(R2) + (x2 - x)/(x2 - x1) f(R1)     (span R1 -> R2 at x)
//
// Points are (x, y, f) with f the value interpolated (pseudo-depth in the notes). On a triangle
// this equals the plane through the three vertices (barycentric interpolation) up to rounding.
// Linear interpolation in window space is right for depth z/w (interp_perspective.hpp explains
// why) but not for attributes, which need the 1/w correction.
//
// Does: the two formulas as written, and their composition for a point in a triangle.
// Does not: perspective correction, the edge walk of a whole triangle (fill_*.hpp give coverage),
//       points outside the triangle (nullopt).
#pragma once

#include <array>
#include <optional>

#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

// f at height y on the edge q1 -> q2 (q1.y != q2.y), the notes' f(R1) formula.
double lerp_edge_at_y(Vec3 q1, Vec3 q2, double y);

// x at height y on the edge q1 -> q2 (q1.y != q2.y).
double edge_x_at_y(Vec3 q1, Vec3 q2, double y);

// f at x on the span r1 -> r2 (r1.x != r2.x), the notes' f(P) formula.
double lerp_span_at_x(Vec3 r1, Vec3 r2, double x);

// Edges first, then across, for the point p of the triangle (x, y, f) vertices; nullopt when p
// is outside the closed triangle or the triangle has no extent in y.
std::optional<double> bilinear_depth_in_triangle(const std::array<Vec3, 3>& triangle, Vec2 p);

}  // namespace rastercmp::methods
