#include "cpu_raster/methods/interp_perspective.hpp"

namespace rastercmp::methods {

std::array<double, 3> barycentric_window(const std::array<Vec2, 3>& pos_window, Vec2 p) {
  const Vec2 a = pos_window[0], b = pos_window[1], c = pos_window[2];
  const double area2 = cross(b - a, c - a);
  const double l1 = cross(p - a, c - a) / area2;  // weight of b
  const double l2 = cross(b - a, p - a) / area2;  // weight of c
  return {1 - l1 - l2, l1, l2};
}

double interpolate_linear(const std::array<double, 3>& weights_window, const std::array<double, 3>& attribute) {
  return weights_window[0] * attribute[0] + weights_window[1] * attribute[1] + weights_window[2] * attribute[2];
}

double interpolate_perspective(const std::array<double, 3>& weights_window, const std::array<double, 3>& attribute,
                               const std::array<double, 3>& w_clip) {
  double numerator = 0, denominator = 0;
  for (size_t i = 0; i < 3; ++i) {
    numerator += weights_window[i] * attribute[i] / w_clip[i];
    denominator += weights_window[i] / w_clip[i];
  }
  return numerator / denominator;
}

}  // namespace rastercmp::methods
