#include "cpu_raster/methods/pseudo_depth.hpp"

#include <stdexcept>

namespace rastercmp::methods {

double pseudo_depth(double z_eye, double near_z, double far_z) {
  if (near_z == far_z || z_eye == 0) throw std::invalid_argument("pseudo_depth: needs near != far and z != 0");
  return 2 * far_z * near_z / ((far_z - near_z) * z_eye) - (far_z + near_z) / (far_z - near_z);
}

double eye_z_from_pseudo_depth(double pseudo, double near_z, double far_z) {
  if (near_z == far_z) throw std::invalid_argument("eye_z_from_pseudo_depth: needs near != far");
  return 2 * far_z * near_z / ((far_z - near_z) * pseudo + far_z + near_z);
}

}  // namespace rastercmp::methods
