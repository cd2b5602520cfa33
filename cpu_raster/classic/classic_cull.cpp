#include "cpu_raster/classic/classic_cull.hpp"

#include "cpu_raster/methods/cull_back_face.hpp"

namespace rastercmp::cpu::classic {
namespace {

methods::Vec3 xyw(const glm::vec4& p) { return {p.x, p.y, p.w}; }

constexpr methods::Vec4 kEyeAtOrigin{0, 0, 0, 1};

}  // namespace

NormalDotView normal_dot_view(const std::array<glm::vec4, 3>& pos_clip, CullMode cull, FrontFace front_face) {
  NormalDotView test;
  const methods::Vec3 v0 = xyw(pos_clip[0]), v1 = xyw(pos_clip[1]), v2 = xyw(pos_clip[2]);
  test.normal = methods::cross(v1 - v0, v2 - v0);  // outward for a counter-clockwise front face
  if (front_face == FrontFace::Clockwise) test.normal = test.normal * -1.0;
  test.view = methods::view_vector(v0, kEyeAtOrigin);
  test.n_dot_v = methods::normal_dot_view(test.normal, v0, kEyeAtOrigin);
  test.back = methods::is_back_face(test.normal, v0, kEyeAtOrigin, methods::EdgeOnFace::Cull);
  test.culled = cull == CullMode::FrontAndBack || (cull == CullMode::Back && test.back) ||
                (cull == CullMode::Front && !test.back);
  return test;
}

}  // namespace rastercmp::cpu::classic
