#include "cpu_raster/methods/cull_back_face.hpp"

namespace rastercmp::methods {

Vec3 view_vector(Vec3 point_on_face, Vec4 viewer) {
  // V = viewer - point for an eye point, the direction itself for a viewer at infinity.
  return viewer.w != 0 ? Vec3{viewer.x, viewer.y, viewer.z} * (1.0 / viewer.w) - point_on_face
                       : Vec3{viewer.x, viewer.y, viewer.z};
}

bool is_back_face(Vec3 outward_normal, Vec3 point_on_face, Vec4 viewer, EdgeOnFace edge_on) {
  const double n_dot_v = normal_dot_view(outward_normal, point_on_face, viewer);
  return edge_on == EdgeOnFace::Cull ? n_dot_v <= 0 : n_dot_v < 0;
}

}  // namespace rastercmp::methods
