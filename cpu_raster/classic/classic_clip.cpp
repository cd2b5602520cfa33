#include "cpu_raster/classic/classic_clip.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cpu_raster/methods/clip_line_cohen_sutherland_3d.hpp"
#include "cpu_raster/methods/clip_polygon_sutherland_hodgman.hpp"

namespace rastercmp::cpu::classic {
namespace {

// Vulkan's clip volume (0 <= z <= w, docs/lavapipe-rules.md §1.3); without depth clip the z planes are
// moved out of reach.
methods::ClipVolume vulkan_volume(bool depth_clip) {
  methods::ClipVolume volume = methods::homogeneous_volume(methods::ClipDepthRange::ZeroToOne);
  if (!depth_clip) {
    volume.bound[size_t(methods::ClipPlane::ZLow)] = -std::numeric_limits<double>::max();
    volume.bound[size_t(methods::ClipPlane::ZHigh)] = std::numeric_limits<double>::max();
  }
  return volume;
}

methods::Vec4 to_vec4(const glm::vec4& p) { return {p.x, p.y, p.z, p.w}; }

bool finite(const glm::vec4& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w);
}

// A vertex the clipper returns: the original one when it kept it, otherwise a new vertex with
// the C viewport transform (docs/lavapipe-rules.md §1.6).
template <size_t N>
ClipVertex vertex_from(const methods::Vec4& pos, const std::array<ClipVertex, N>& originals,
                       const ViewportTransform& viewport) {
  for (const ClipVertex& original : originals)
    if (to_vec4(original.pos_clip) == pos) return original;
  ClipVertex made;
  made.pos_clip = glm::vec4(float(pos.x), float(pos.y), float(pos.z), float(pos.w));
  made.window = window_from_clip_c(made.pos_clip, viewport);
  made.made_by_clipper = true;
  return made;
}

// Outcodes of the primitive's vertices: {OR, AND}.
template <size_t N>
std::array<uint8_t, 2> outcodes(const std::array<ClipVertex, N>& vertices, const methods::ClipVolume& volume) {
  uint8_t any = 0, all = 0xFF;
  for (const ClipVertex& v : vertices) {
    const uint8_t code = methods::outcode(volume, to_vec4(v.pos_clip));
    any |= code;
    all &= code;
  }
  return {any, all};
}

// Liang–Barsky on the six planes: entering planes raise t_in, leaving planes lower t_out.
ClassicClippedLine liang_barsky_homogeneous(const std::array<ClipVertex, 2>& line, const methods::ClipVolume& volume,
                                            const ViewportTransform& viewport) {
  const methods::Vec4 p0 = to_vec4(line[0].pos_clip), p1 = to_vec4(line[1].pos_clip);
  ClassicClippedLine result;
  result.passes = 1;
  double t_in = 0, t_out = 1;
  for (methods::ClipPlane plane : methods::kClipPlanes) {
    const double d0 = methods::plane_distance(volume, plane, p0), d1 = methods::plane_distance(volume, plane, p1);
    if (d0 < 0 && d1 < 0) return result;
    if (d0 < 0) t_in = std::max(t_in, d0 / (d0 - d1));
    if (d1 < 0) t_out = std::min(t_out, d0 / (d0 - d1));
    if (t_in > t_out) return result;
  }
  result.visible = true;
  const methods::Vec4 q0 = t_in == 0 ? p0 : methods::lerp(p0, p1, t_in);
  const methods::Vec4 q1 = t_out == 1 ? p1 : methods::lerp(p0, p1, t_out);
  result.clips = int(t_in != 0) + int(t_out != 1);
  result.line = {vertex_from(q0, line, viewport), vertex_from(q1, line, viewport)};
  return result;
}

}  // namespace

std::vector<std::array<ClipVertex, 3>> clip_triangle_sutherland_hodgman(const std::array<ClipVertex, 3>& triangle,
                                                                        const ViewportTransform& viewport,
                                                                        bool depth_clip) {
  for (const ClipVertex& v : triangle)
    if (!finite(v.pos_clip)) return {};
  const methods::ClipVolume volume = vulkan_volume(depth_clip);
  const auto [any, all] = outcodes(triangle, volume);
  if (any == 0) return {triangle};
  if (all != 0) return {};
  std::vector<methods::Vec4> subject;
  for (const ClipVertex& v : triangle) subject.push_back(to_vec4(v.pos_clip));
  const std::vector<methods::Vec4> polygon = methods::clip_polygon_sutherland_hodgman(subject, volume);
  std::vector<std::array<ClipVertex, 3>> fan;
  for (size_t k = 2; k < polygon.size(); ++k)  // (p0, pk-1, pk), as lavapipe's clipper emits (§1.6)
    fan.push_back({vertex_from(polygon[0], triangle, viewport), vertex_from(polygon[k - 1], triangle, viewport),
                   vertex_from(polygon[k], triangle, viewport)});
  return fan;
}

ClassicClippedLine clip_line_classic(const std::array<ClipVertex, 2>& line, const ViewportTransform& viewport,
                                     bool depth_clip, LineClipper clipper) {
  ClassicClippedLine result;
  if (!finite(line[0].pos_clip) || !finite(line[1].pos_clip)) return result;
  const methods::ClipVolume volume = vulkan_volume(depth_clip);
  const auto [any, all] = outcodes(line, volume);
  if (all != 0) return result;
  if (any == 0) {
    result.visible = true;
    result.line = line;
    return result;
  }
  if (clipper == LineClipper::LiangBarsky) return liang_barsky_homogeneous(line, volume, viewport);
  const methods::CohenSutherland3dResult cs =
      methods::clip_line_cohen_sutherland_3d(to_vec4(line[0].pos_clip), to_vec4(line[1].pos_clip), volume);
  result.passes = cs.passes;
  result.clips = cs.clips;
  if (!cs.accepted) return result;
  result.visible = true;
  result.line = {vertex_from(cs.p0, line, viewport), vertex_from(cs.p1, line, viewport)};
  return result;
}

}  // namespace rastercmp::cpu::classic
