#include "cpu_raster/exact/pipeline_cull.hpp"

namespace rastercmp::cpu {
namespace {

bool culls_front(CullMode cull) { return cull == CullMode::Front || cull == CullMode::FrontAndBack; }
bool culls_back(CullMode cull) { return cull == CullMode::Back || cull == CullMode::FrontAndBack; }

}  // namespace

float pipeline_cull_determinant(const std::array<WindowVertex, 3>& w) {
  const float ex = w[0].x - w[2].x;
  const float ey = w[0].y - w[2].y;
  const float fx = w[1].x - w[2].x;
  const float fy = w[1].y - w[2].y;
  return ex * fy - ey * fx;
}

bool pipeline_cull_drops(float det, CullMode cull, FrontFace front_face) {
  if (det != 0.0f) {  // also taken by NaN, as in the C code
    const bool ccw = det < 0.0f;
    const bool front = ccw == (front_face == FrontFace::CounterClockwise);
    return front ? culls_front(cull) : culls_back(cull);
  }
  return culls_back(cull);  // zero float area counts as back-facing
}

}  // namespace rastercmp::cpu
