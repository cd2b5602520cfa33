#include "cpu_raster/classic/classic_clip.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "cpu_raster/methods/clip_line_cohen_sutherland.hpp"
#include "cpu_raster/methods/clip_line_cohen_sutherland_3d.hpp"
#include "cpu_raster/methods/clip_line_cyrus_beck.hpp"
#include "cpu_raster/methods/clip_polygon_sutherland_hodgman.hpp"
#include "cpu_raster/methods/clip_polygon_weiler_atherton.hpp"
#include "cpu_raster/methods/interp_perspective.hpp"
#include "model/errors.hpp"

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
  result.trace.trivial = false;
  double& t_in = result.trace.t_in;
  double& t_out = result.trace.t_out;
  for (methods::ClipPlane plane : methods::kClipPlanes) {
    const double d0 = methods::plane_distance(volume, plane, p0), d1 = methods::plane_distance(volume, plane, p1);
    LiangBarskyPlane& row = result.trace.liang_barsky.emplace_back();
    row.plane = plane, row.d0 = d0, row.d1 = d1;
    if (d0 < 0 && d1 < 0) return result;
    if (d0 < 0 || d1 < 0) row.t = d0 / (d0 - d1);
    row.entering = d0 < 0, row.leaving = d1 < 0;
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

// The viewport rectangle in window space: where -w <= x, y <= w lands after the divide.
methods::Rect2 viewport_rect(const ViewportTransform& viewport) {
  const double x0 = double(viewport.translate[0]) - double(viewport.scale[0]);
  const double x1 = double(viewport.translate[0]) + double(viewport.scale[0]);
  const double y0 = double(viewport.translate[1]) - double(viewport.scale[1]);
  const double y1 = double(viewport.translate[1]) + double(viewport.scale[1]);
  return {std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)};
}

methods::Vec2 window_xy(const ClipVertex& v) { return {v.window.x, v.window.y}; }

// 2-D clipping needs what the divide keeps: w > 0 and, with depth clip, 0 <= z <= w (the registry
// refuses scenes that break this; a primitive that still does is reported, never clipped wrongly).
template <size_t N>
void require_2d(const std::array<ClipVertex, N>& vertices, bool depth_clip) {
  for (const ClipVertex& v : vertices) {
    if (!(v.pos_clip.w > 0)) throw NotSupportedError("a 2-D clipper got a vertex with w <= 0 (behind the eye)");
    if (depth_clip && !(v.pos_clip.z >= 0 && v.pos_clip.z <= v.pos_clip.w))
      throw NotSupportedError("a 2-D clipper got a vertex outside the depth clip planes");
  }
}

// A vertex a 2-D clipper made at window point q with window-space weights l of the originals:
// 1/w and every clip coordinate over w are affine in window space, so the clip position is the
// perspective-correct blend; its window z comes from it (C viewport transform), x and y are the clipper's.
template <size_t N>
ClipVertex vertex_at_window(const std::array<ClipVertex, N>& originals, const std::array<double, N>& l, methods::Vec2 q,
                            const ViewportTransform& viewport) {
  for (const ClipVertex& original : originals)
    if (window_xy(original) == q) return original;
  double inv_w = 0;
  methods::Vec4 clip{0, 0, 0, 0};
  for (size_t k = 0; k < N; ++k) {
    const double weight = l[k] / double(originals[k].pos_clip.w);
    inv_w += weight;
    clip = {clip.x + weight * originals[k].pos_clip.x, clip.y + weight * originals[k].pos_clip.y,
            clip.z + weight * originals[k].pos_clip.z, clip.w + weight * originals[k].pos_clip.w};
  }
  ClipVertex made;
  made.pos_clip = glm::vec4(float(clip.x / inv_w), float(clip.y / inv_w), float(clip.z / inv_w), float(clip.w / inv_w));
  made.window = window_from_clip_c(made.pos_clip, viewport);
  made.window.x = float(q.x);
  made.window.y = float(q.y);
  made.made_by_clipper = true;
  return made;
}

// The parameter of point q along the window segment a -> b (by its longer axis).
double window_parameter(methods::Vec2 a, methods::Vec2 b, methods::Vec2 q) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  if (dx == 0 && dy == 0) return 0;
  return std::abs(dx) >= std::abs(dy) ? (q.x - a.x) / dx : (q.y - a.y) / dy;
}

ClassicClippedLine clip_line_2d(const std::array<ClipVertex, 2>& line, const ViewportTransform& viewport,
                                LineClipper clipper) {
  const methods::Rect2 rect = viewport_rect(viewport);
  const methods::Segment2 segment{window_xy(line[0]), window_xy(line[1])};
  ClassicClippedLine result;
  result.trace.trivial = false;
  result.trace.window = rect;
  methods::Segment2 visible;
  if (clipper == LineClipper::CohenSutherland) {
    methods::CohenSutherlandResult cs = methods::clip_line_cohen_sutherland(segment, rect);
    result.passes = cs.passes;
    result.clips = cs.clips;
    result.trace.passes_2d = std::move(cs.trace);
    if (!cs.accepted) return result;
    visible = cs.segment;
  } else {
    const methods::Polygon2 window{
        {rect.x_min, rect.y_min}, {rect.x_max, rect.y_min}, {rect.x_max, rect.y_max}, {rect.x_min, rect.y_max}};
    methods::CyrusBeckResult cb = methods::clip_line_cyrus_beck(segment, window);
    result.passes = 1;
    result.trace.t_in = cb.t_in, result.trace.t_out = cb.t_out;
    result.trace.cyrus_beck = std::move(cb.trace);
    if (!cb.accepted) return result;
    result.clips = int(cb.t_in != 0) + int(cb.t_out != 1);
    visible = cb.segment;
  }
  result.visible = true;
  std::array<ClipVertex, 2> ends;
  const methods::Vec2 q[2] = {visible.p0, visible.p1};
  for (size_t k = 0; k < 2; ++k) {
    const double t = window_parameter(segment.p0, segment.p1, q[k]);
    ends[k] = vertex_at_window(line, std::array<double, 2>{1 - t, t}, q[k], viewport);
  }
  result.line = ends;
  return result;
}

// What both polygon clippers decide before clipping: a non-finite vertex drops the triangle, one
// wholly inside passes unchanged, one wholly outside a plane is dropped; nullopt: clip it.
std::optional<std::vector<std::array<ClipVertex, 3>>> trivial_clip(const std::array<ClipVertex, 3>& triangle,
                                                                   const methods::ClipVolume& volume) {
  for (const ClipVertex& v : triangle)
    if (!finite(v.pos_clip)) return std::vector<std::array<ClipVertex, 3>>{};
  const auto [any, all] = outcodes(triangle, volume);
  if (any == 0) return std::vector<std::array<ClipVertex, 3>>{triangle};
  if (all != 0) return std::vector<std::array<ClipVertex, 3>>{};
  return std::nullopt;
}

}  // namespace

std::vector<std::array<ClipVertex, 3>> clip_triangle_weiler_atherton(const std::array<ClipVertex, 3>& triangle,
                                                                     const ViewportTransform& viewport,
                                                                     bool depth_clip) {
  const methods::ClipVolume volume = vulkan_volume(depth_clip);
  if (auto decided = trivial_clip(triangle, volume)) return *decided;
  require_2d(triangle, depth_clip);
  const std::array<methods::Vec2, 3> xy{window_xy(triangle[0]), window_xy(triangle[1]), window_xy(triangle[2])};
  const methods::Polygon2 subject(xy.begin(), xy.end());
  const double area = methods::signed_area(subject);
  if (area == 0) return {};  // no area in window space: the set-up drops it anyway
  const methods::Rect2 rect = viewport_rect(viewport);
  const methods::Polygon2 window{
      {rect.x_min, rect.y_min}, {rect.x_max, rect.y_min}, {rect.x_max, rect.y_max}, {rect.x_min, rect.y_max}};
  const methods::WeilerAthertonResult wa = methods::clip_polygon_weiler_atherton(subject, window);
  if (wa.degenerate)
    throw NotSupportedError(
        "clip=weiler_atherton: a triangle touches the viewport boundary with a vertex or along an edge "
        "(degenerate contact, which the method does not resolve)");
  std::vector<std::array<ClipVertex, 3>> fan;
  for (methods::Polygon2 piece : wa.polygons) {
    if ((methods::signed_area(piece) > 0) != (area > 0)) std::reverse(piece.begin(), piece.end());  // keep facing
    std::vector<ClipVertex> made;
    for (const methods::Vec2& q : piece)
      made.push_back(vertex_at_window(triangle, methods::barycentric_window(xy, q), q, viewport));
    for (size_t k = 2; k < made.size(); ++k) fan.push_back({made[0], made[k - 1], made[k]});
  }
  return fan;
}

std::vector<std::array<ClipVertex, 3>> clip_triangle_sutherland_hodgman(const std::array<ClipVertex, 3>& triangle,
                                                                        const ViewportTransform& viewport,
                                                                        bool depth_clip) {
  const methods::ClipVolume volume = vulkan_volume(depth_clip);
  if (auto decided = trivial_clip(triangle, volume)) return *decided;
  std::vector<methods::Vec4> subject;
  for (const ClipVertex& v : triangle) subject.push_back(to_vec4(v.pos_clip));
  const std::vector<methods::Vec4> polygon = methods::clip_polygon_sutherland_hodgman(subject, volume);
  std::vector<std::array<ClipVertex, 3>> fan;
  for (size_t k = 2; k < polygon.size(); ++k)  // (p0, pk-1, pk), as lavapipe's clipper emits (§1.6)
    fan.push_back({vertex_from(polygon[0], triangle, viewport), vertex_from(polygon[k - 1], triangle, viewport),
                   vertex_from(polygon[k], triangle, viewport)});
  return fan;
}

uint8_t clip_space_outcode(const ClipVertex& vertex, bool depth_clip) {
  return methods::outcode(vulkan_volume(depth_clip), to_vec4(vertex.pos_clip));
}

ClassicClippedLine clip_line_classic(const std::array<ClipVertex, 2>& line, const ViewportTransform& viewport,
                                     bool depth_clip, LineClipper clipper) {
  ClassicClippedLine result;
  if (!finite(line[0].pos_clip) || !finite(line[1].pos_clip)) return result;
  const methods::ClipVolume volume = vulkan_volume(depth_clip);
  const auto [any, all] = outcodes(line, volume);
  const auto with_codes = [&](ClassicClippedLine r) {
    r.trace.code_p0 = methods::outcode(volume, to_vec4(line[0].pos_clip));
    r.trace.code_p1 = methods::outcode(volume, to_vec4(line[1].pos_clip));
    return r;
  };
  if (all != 0) return with_codes(result);
  if (any == 0) {
    result.visible = true;
    result.line = line;
    return with_codes(result);
  }
  if (clipper == LineClipper::LiangBarsky) return with_codes(liang_barsky_homogeneous(line, volume, viewport));
  if (clipper == LineClipper::CohenSutherland || clipper == LineClipper::CyrusBeck) {
    require_2d(line, depth_clip);
    return with_codes(clip_line_2d(line, viewport, clipper));
  }
  methods::CohenSutherland3dResult cs =
      methods::clip_line_cohen_sutherland_3d(to_vec4(line[0].pos_clip), to_vec4(line[1].pos_clip), volume);
  result.passes = cs.passes;
  result.clips = cs.clips;
  result.trace.trivial = false;
  result.trace.passes_3d = std::move(cs.trace);
  result = with_codes(std::move(result));
  if (!cs.accepted) return result;
  result.visible = true;
  result.line = {vertex_from(cs.p0, line, viewport), vertex_from(cs.p1, line, viewport)};
  return result;
}

}  // namespace rastercmp::cpu::classic
