#include "cpu_raster/methods/visibility_raster.hpp"

#include "cpu_raster/methods/fill_polygon_rule.hpp"

namespace rastercmp::methods {

namespace {

OwnerImage blank_image(int32_t width, int32_t height) {
  OwnerImage image;
  image.width = width;
  image.height = height;
  image.owner.assign(size_t(width) * size_t(height), kNoOwner);
  return image;
}

// Calls covered(x, y, depth) for each pixel the polygon covers; edge-on polygons cover none.
template <typename Covered>
void rasterize(const Polygon3& polygon, int32_t width, int32_t height, Covered covered) {
  const Vec3 n = newell_normal(polygon.vertices);
  if (n.z == 0) return;
  const Plane3 plane = plane_of(polygon);
  Polygon2 projected;
  for (const Vec3& v : polygon.vertices) projected.push_back({v.x, v.y});
  PolygonFillOptions options;
  options.rule = FillRule::NonZero;
  options.sample_offset = 0.5;
  options.bounds = {0, 0, width, height};
  for (const Span& span : fill_polygon_rule(projected, options)) {
    const double y_sample = span.y + 0.5;
    for (int32_t x = span.x_begin; x < span.x_end; ++x) {
      const double x_sample = x + 0.5;
      const double z = -(plane.normal.x * x_sample + plane.normal.y * y_sample + plane.d) / plane.normal.z;
      covered(x, span.y, z);
    }
  }
}

}  // namespace

OwnerImage paint_in_order(const std::vector<Polygon3>& polygons_back_to_front, int32_t width, int32_t height) {
  OwnerImage image = blank_image(width, height);
  for (const Polygon3& polygon : polygons_back_to_front) {
    rasterize(polygon, width, height,
              [&](int32_t x, int32_t y, double) { image.owner[size_t(y) * size_t(width) + size_t(x)] = polygon.id; });
  }
  return image;
}

OwnerImage paint_with_zbuffer(const std::vector<Polygon3>& polygons, int32_t width, int32_t height) {
  OwnerImage image = blank_image(width, height);
  image.depth.assign(image.owner.size(), std::numeric_limits<double>::infinity());
  for (const Polygon3& polygon : polygons) {
    rasterize(polygon, width, height, [&](int32_t x, int32_t y, double z) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      if (z < image.depth[i]) {
        image.depth[i] = z;
        image.owner[i] = polygon.id;
      }
    });
  }
  return image;
}

}  // namespace rastercmp::methods
