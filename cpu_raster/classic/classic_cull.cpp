#include "cpu_raster/classic/classic_cull.hpp"

#include "cpu_raster/methods/cull_back_face.hpp"

namespace rastercmp::cpu::classic {
namespace {

methods::Vec3 xyw(const glm::vec4& p) { return {p.x, p.y, p.w}; }

constexpr methods::Vec4 kEyeAtOrigin{0, 0, 0, 1};

}  // namespace

bool normal_dot_view_culls(const std::array<glm::vec4, 3>& pos_clip, CullMode cull, FrontFace front_face) {
  if (cull == CullMode::None) return false;
  if (cull == CullMode::FrontAndBack) return true;
  const methods::Vec3 v0 = xyw(pos_clip[0]), v1 = xyw(pos_clip[1]), v2 = xyw(pos_clip[2]);
  methods::Vec3 normal = methods::cross(v1 - v0, v2 - v0);  // outward for a counter-clockwise front face
  if (front_face == FrontFace::Clockwise) normal = normal * -1.0;
  const bool back = methods::is_back_face(normal, v0, kEyeAtOrigin, methods::EdgeOnFace::Cull);
  return cull == CullMode::Back ? back : !back;
}

}  // namespace rastercmp::cpu::classic
