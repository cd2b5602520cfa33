// Cohen–Sutherland clipping of a 3D segment against a box or the homogeneous clip volume, with
// 6-bit outcodes. Notes: lecture-rasterization-depth-sorting-culling.txt "Cohen Sutherland in 3D"
// ("Use 6-bit outcodes; when needed, clip line segment against planes"); the 2D loop of
// clip_line_cohen_sutherland.hpp.
//
// Does: trivial accept (OR == 0) / reject (AND != 0), then per pass replaces the outside endpoint
//       (p0's side first) by its crossing with the lowest-numbered plane it is outside of
//       (clip_volume.hpp order x low, x high, y low, y high, z low, z high); counts passes/clips.
//       Homogeneous clipping happens before the divide, so w may vary along the segment.
// Does not: divide by w (the caller divides after clipping), or accept a segment that only
//       grazes an edge of the volume within rounding (rejected after the pass bound).
#pragma once

#include <vector>

#include "cpu_raster/methods/clip_volume.hpp"

namespace rastercmp::methods {

// One pass: the 6-bit outcodes of the current endpoints and what the pass did with them.
struct CohenSutherland3dPass {
  uint8_t code_p0 = 0, code_p1 = 0;
  bool clipped = false;               // false: this pass accepted (OR == 0) or rejected (AND != 0)
  bool clipped_p0 = false;            // the p0 end was replaced (else p1)
  ClipPlane plane = ClipPlane::XLow;  // the plane it was cut at, when clipped
};

struct CohenSutherland3dResult {
  bool accepted = false;
  Vec4 p0, p1;                               // the visible part (w = 1 for the box form); meaningful only when accepted
  int passes = 0;                            // outcode evaluations of the pair, including the final accept/reject
  int clips = 0;                             // endpoint replacements
  std::vector<CohenSutherland3dPass> trace;  // one row per pass
};

inline constexpr int kCohenSutherland3dMaxPasses = 24;  // grazing a box edge: see the 2D header

CohenSutherland3dResult clip_line_cohen_sutherland_3d(Vec4 p0, Vec4 p1, const ClipVolume& volume);

// Convenience: the box form with points (x, y, z, 1).
CohenSutherland3dResult clip_line_cohen_sutherland_box(Vec3 p0, Vec3 p1, const Box3& box);

}  // namespace rastercmp::methods
