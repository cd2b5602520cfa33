#include "experiments/coverage_model.hpp"

#include <algorithm>
#include <cmath>

namespace rastercmp::experiments {
namespace {

// §2.2: 256 x rounded to nearest (cvtps2dq: halves to even), or halves away (util_iround).
double snap(double x_pixels, ModelVertices vertices) {
  const double fixed = 256 * x_pixels;
  if (vertices == ModelVertices::Real) return x_pixels;
  const double rounded = vertices == ModelVertices::SnapHalfEven ? std::nearbyint(fixed) : std::round(fixed);
  return rounded / 256;
}

WindowTriangle with_vertices(const WindowTriangle& t, ModelVertices vertices) {
  WindowTriangle out;
  for (size_t i = 0; i < 3; ++i) out[i] = {snap(t[i].x, vertices), snap(t[i].y, vertices)};
  return out;
}

double twice_area(const WindowTriangle& t) {
  return (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x);
}

// Whether the sample at `p` is covered: every edge function, oriented so the inside is positive,
// is > 0, or == 0 on an edge the tie rule gives the triangle. Top-left in y-down window space:
// the inside lies at larger x (a left edge), or the edge is horizontal with the inside at larger
// y (a top edge) — lavapipe-rules §2.4.
bool covers(const WindowTriangle& t, double sign, glm::dvec2 p, ModelTies ties) {
  for (size_t i = 0; i < 3; ++i) {
    const glm::dvec2 a = t[i], b = t[(i + 1) % 3];
    const double e = sign * ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x));
    if (e > 0) continue;
    if (e < 0 || ties == ModelTies::None) return false;
    if (ties == ModelTies::All) continue;
    const double inward_x = -sign * (b.y - a.y), inward_y = sign * (b.x - a.x);
    if (!(inward_x > 0 || (inward_x == 0 && inward_y > 0))) return false;
  }
  return true;
}

}  // namespace

std::vector<int32_t> model_owners(const DesignTriangles& design, CoverageRule rule) {
  std::vector<int32_t> owner(size_t(design.width) * design.height, -1);
  for (size_t k = 0; k < design.triangles.size(); ++k) {
    const WindowTriangle& real = design.triangles[k];
    if (twice_area(with_vertices(real, ModelVertices::SnapHalfEven)) == 0) continue;  // the exact set-up's cull
    const WindowTriangle t = with_vertices(real, rule.vertices);
    const double area = twice_area(t);
    if (area == 0) continue;
    double x0 = t[0].x, x1 = x0, y0 = t[0].y, y1 = y0;
    for (const glm::dvec2& v : t) x0 = std::min(x0, v.x), x1 = std::max(x1, v.x), y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
    const int64_t px0 = std::max<int64_t>(0, int64_t(std::floor(x0 - 0.5))),
                  px1 = std::min<int64_t>(design.width - 1, int64_t(std::ceil(x1 - 0.5))),
                  py0 = std::max<int64_t>(0, int64_t(std::floor(y0 - 0.5))),
                  py1 = std::min<int64_t>(design.height - 1, int64_t(std::ceil(y1 - 0.5)));
    for (int64_t py = py0; py <= py1; ++py)
      for (int64_t px = px0; px <= px1; ++px) {
        int32_t& o = owner[size_t(py) * design.width + size_t(px)];
        if (o < 0 && covers(t, area > 0 ? 1 : -1, {double(px) + 0.5, double(py) + 0.5}, rule.ties)) o = int32_t(k);
      }
  }
  return owner;
}

uint64_t model_mismatch(const DesignTriangles& design, CoverageRule method, CoverageRule reference) {
  const std::vector<int32_t> a = model_owners(design, method), b = model_owners(design, reference);
  uint64_t differ = 0;
  for (size_t i = 0; i < a.size(); ++i) differ += a[i] != b[i];
  return differ;
}

}  // namespace rastercmp::experiments
