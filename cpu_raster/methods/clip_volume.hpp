// The six clip planes of a 3D box or of the homogeneous clip volume, as one description shared
// by the 3D Cohen–Sutherland line clipper and the homogeneous Sutherland–Hodgman polygon clipper.
// Notes: lecture-rasterization-depth-sorting-culling.txt "Cohen Sutherland in 3D" (6-bit
// outcodes) and "Pipeline Clipping of Polygons" (add front and back clippers).
//
// Plane k keeps the points with  sign_k * (coord_k - bound_k * w) >= 0:
//   box (points with w = 1):  x_min <= x <= x_max, y_min <= y <= y_max, z_min <= z <= z_max;
//   homogeneous (clip space): -w <= x <= w, -w <= y <= w, and 0 <= z <= w (Vulkan) or
//                             -w <= z <= w (OpenGL, the notes' canonical view volume).
// Outcode bit of plane k is 1 << k: 1 x low, 2 x high, 4 y low, 8 y high, 16 z low (near),
// 32 z high (far) — the notes' Y0Y1X0X1 layout extended by Z0Z1.
//
// Does: signed plane distances, outcodes, the crossing parameter of a segment with a plane,
//       snapping a crossing point exactly onto the plane.
// Does not: add a w > 0 plane (points with w <= 0 fail -w <= x <= w already, except the origin).
#pragma once

#include <array>
#include <cstdint>

#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

enum class ClipDepthRange { ZeroToOne, MinusOneToOne };

enum class ClipPlane : uint8_t { XLow = 0, XHigh, YLow, YHigh, ZLow, ZHigh };
inline constexpr std::array<ClipPlane, 6> kClipPlanes{ClipPlane::XLow,  ClipPlane::XHigh, ClipPlane::YLow,
                                                      ClipPlane::YHigh, ClipPlane::ZLow,  ClipPlane::ZHigh};

struct ClipVolume {
  std::array<double, 6> bound{};  // bound_k per ClipPlane, in units of w
};

ClipVolume box_volume(const Box3& box);
ClipVolume homogeneous_volume(ClipDepthRange depth_range);

// sign_k * (coord_k - bound_k * w): >= 0 inside plane k.
double plane_distance(const ClipVolume& volume, ClipPlane plane, Vec4 p);

inline uint8_t outcode_bit(ClipPlane plane) { return uint8_t(1u << uint8_t(plane)); }
uint8_t outcode(const ClipVolume& volume, Vec4 p);

// The point of segment inside -> outside (or either way) on `plane`: lerp at t = d_a / (d_a - d_b),
// with the plane's coordinate then set exactly to bound * w so the point tests inside the plane.
Vec4 intersect_plane(const ClipVolume& volume, ClipPlane plane, Vec4 a, Vec4 b);

}  // namespace rastercmp::methods
