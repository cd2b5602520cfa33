#include "cpu_raster/methods/visibility_painter.hpp"

#include <algorithm>
#include <limits>

namespace rastercmp::methods {

double painter_key(const Polygon3& polygon, PainterKey key) {
  if (key == PainterKey::FarthestVertex) {
    double z = -std::numeric_limits<double>::infinity();
    for (const Vec3& v : polygon.vertices) z = std::max(z, v.z);
    return z;
  }
  double sum = 0;
  for (const Vec3& v : polygon.vertices) sum += v.z;
  return polygon.vertices.empty() ? 0 : sum / double(polygon.vertices.size());
}

std::vector<size_t> painter_order(const std::vector<Polygon3>& polygons, PainterKey key) {
  std::vector<double> keys(polygons.size());
  std::vector<size_t> order(polygons.size());
  for (size_t i = 0; i < polygons.size(); ++i) {
    keys[i] = painter_key(polygons[i], key);
    order[i] = i;
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return keys[a] > keys[b]; });
  return order;
}

}  // namespace rastercmp::methods
