// Back-face culling by the sign of N.V. Notes: notes-line-clipping-hidden-surface.txt "Back Face
// Removal" (V points from the surface towards the viewer; "Remove the surface as hidden if
// N.V <= 0"; along the z axis, V = (0, 0, 1) and the rule becomes "remove if c <= 0" for the plane
// a x + b y + c z + d = 0); lecture-graphics-pipeline-cyrus-beck.txt "Backface Culling" (V from
// the eye to the point; cull if N.V > 0 — the same test with V reversed, except that it keeps
// edge-on faces).
//
// Does: the test for a face given its outward normal and one of its points, for an eye point or a
//       viewer at infinity (homogeneous viewer as in visibility_bsp.hpp), with the edge-on case
//       chosen by the caller.
// Does not: decide facing from window-space winding (the rasterizer's cull mode does that with
//       the signed area), or make a scene of open or non-closed objects correct.
#pragma once

#include "cpu_raster/methods/geometry.hpp"

namespace rastercmp::methods {

enum class EdgeOnFace {
  Cull,  // notes-line-clipping-hidden-surface.txt: hidden if N.V <= 0
  Keep,  // lecture-graphics-pipeline-cyrus-beck.txt: culled only if N.(point - eye) > 0
};

// V: from the point towards the viewer; viewer (x, y, z, 1) an eye point, or (x, y, z, 0) the
// direction towards a viewer at infinity.
Vec3 view_vector(Vec3 point_on_face, Vec4 viewer);

// N.V, the number is_back_face decides on.
inline double normal_dot_view(Vec3 outward_normal, Vec3 point_on_face, Vec4 viewer) {
  return dot(outward_normal, view_vector(point_on_face, viewer));
}

// viewer: (x, y, z, 1) an eye point, or (x, y, z, 0) the direction towards a viewer at infinity.
bool is_back_face(Vec3 outward_normal, Vec3 point_on_face, Vec4 viewer, EdgeOnFace edge_on = EdgeOnFace::Cull);

// The notes' special case V = (0, 0, 1): remove a x + b y + c z + d = 0 if c <= 0.
inline bool is_back_face_view_along_z(double c) { return c <= 0; }

}  // namespace rastercmp::methods
