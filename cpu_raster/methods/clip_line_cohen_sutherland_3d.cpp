#include "cpu_raster/methods/clip_line_cohen_sutherland_3d.hpp"

namespace rastercmp::methods {

namespace {

ClipPlane lowest_set_plane(uint8_t code) {
  for (ClipPlane plane : kClipPlanes) {
    if (code & outcode_bit(plane)) return plane;
  }
  return ClipPlane::XLow;  // unreachable for a non-zero code
}

}  // namespace

CohenSutherland3dResult clip_line_cohen_sutherland_3d(Vec4 p0, Vec4 p1, const ClipVolume& volume) {
  CohenSutherland3dResult result;
  while (result.passes < kCohenSutherland3dMaxPasses) {
    ++result.passes;
    const uint8_t code0 = outcode(volume, p0), code1 = outcode(volume, p1);
    CohenSutherland3dPass& pass = result.trace.emplace_back();
    pass.code_p0 = code0, pass.code_p1 = code1;
    if ((code0 | code1) == 0) {
      result.accepted = true;
      result.p0 = p0;
      result.p1 = p1;
      return result;
    }
    if ((code0 & code1) != 0) return result;
    ++result.clips;
    pass.clipped = true;
    pass.clipped_p0 = code0 != 0;
    pass.plane = lowest_set_plane(code0 != 0 ? code0 : code1);
    if (code0 != 0)
      p0 = intersect_plane(volume, pass.plane, p0, p1);
    else
      p1 = intersect_plane(volume, pass.plane, p1, p0);
  }
  return result;
}

CohenSutherland3dResult clip_line_cohen_sutherland_box(Vec3 p0, Vec3 p1, const Box3& box) {
  return clip_line_cohen_sutherland_3d({p0.x, p0.y, p0.z, 1}, {p1.x, p1.y, p1.z, 1}, box_volume(box));
}

}  // namespace rastercmp::methods
