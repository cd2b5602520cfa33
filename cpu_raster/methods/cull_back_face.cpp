#include "cpu_raster/methods/cull_back_face.hpp"

namespace rastercmp::methods {

bool is_back_face(Vec3 outward_normal, Vec3 point_on_face, Vec4 viewer, EdgeOnFace edge_on) {
  // V = viewer - point for an eye point, the direction itself for a viewer at infinity.
  const Vec3 to_viewer = viewer.w != 0 ? Vec3{viewer.x, viewer.y, viewer.z} * (1.0 / viewer.w) - point_on_face
                                       : Vec3{viewer.x, viewer.y, viewer.z};
  const double n_dot_v = dot(outward_normal, to_viewer);
  return edge_on == EdgeOnFace::Cull ? n_dot_v <= 0 : n_dot_v < 0;
}

}  // namespace rastercmp::methods
