#include "cpu_raster/methods/clip_volume.hpp"

namespace rastercmp::methods {

namespace {

double& coord(Vec4& p, ClipPlane plane) {
  switch (plane) {
    case ClipPlane::XLow:
    case ClipPlane::XHigh: return p.x;
    case ClipPlane::YLow:
    case ClipPlane::YHigh: return p.y;
    case ClipPlane::ZLow:
    case ClipPlane::ZHigh: return p.z;
  }
  return p.z;
}

double sign(ClipPlane plane) { return (uint8_t(plane) % 2 == 0) ? 1.0 : -1.0; }

}  // namespace

ClipVolume box_volume(const Box3& box) { return {{box.x_min, box.x_max, box.y_min, box.y_max, box.z_min, box.z_max}}; }

ClipVolume homogeneous_volume(ClipDepthRange depth_range) {
  const double z_low = depth_range == ClipDepthRange::ZeroToOne ? 0.0 : -1.0;
  return {{-1, 1, -1, 1, z_low, 1}};
}

double plane_distance(const ClipVolume& volume, ClipPlane plane, Vec4 p) {
  return sign(plane) * (coord(p, plane) - volume.bound[uint8_t(plane)] * p.w);
}

uint8_t outcode(const ClipVolume& volume, Vec4 p) {
  uint8_t code = 0;
  for (ClipPlane plane : kClipPlanes) {
    if (plane_distance(volume, plane, p) < 0) code |= outcode_bit(plane);
  }
  return code;
}

Vec4 intersect_plane(const ClipVolume& volume, ClipPlane plane, Vec4 a, Vec4 b) {
  const double d_a = plane_distance(volume, plane, a), d_b = plane_distance(volume, plane, b);
  Vec4 p = lerp(a, b, d_a / (d_a - d_b));
  coord(p, plane) = volume.bound[uint8_t(plane)] * p.w;
  return p;
}

}  // namespace rastercmp::methods
