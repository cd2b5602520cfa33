#include "cpu_raster/exact/clip_triangle.hpp"

#include <bit>

#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/float_ops.hpp"

namespace rastercmp::cpu {
namespace {

// A polygon of at most kMaxClippedVertices vertices, held in place (docs/performance-log.md, 4ec5763).
using Polygon = InPlaceList<ClipVertex, kMaxClippedVertices>;

// The intersection of edge (prev -> vert) with the plane, from the vertex nearer the plane (§1.6).
ClipVertex intersect(const ClipVertex& prev, float dp_prev, const ClipVertex& vert, float dp,
                     const ViewportTransform& viewport) {
  const float denom = dp - dp_prev;
  if (dp < 0.0f) {  // going out
    if (-dp < dp_prev) return interpolate_clip_vertex(dp / denom, vert, prev, viewport);
    return interpolate_clip_vertex(-dp_prev / denom, prev, vert, viewport);
  }
  if (-dp_prev < dp) return interpolate_clip_vertex(-dp_prev / denom, prev, vert, viewport);  // coming in
  return interpolate_clip_vertex(dp / denom, vert, prev, viewport);
}

// One Sutherland–Hodgman pass from `in` into `out`; false when the primitive must be discarded.
bool clip_against(const Polygon& in, uint32_t plane, const ViewportTransform& viewport, Polygon& out) {
  out.clear();
  const ClipVertex* prev = &in[0];
  float dp_prev = plane_distance(prev->pos_clip, plane);
  if (is_inf_or_nan(dp_prev)) return false;
  for (size_t i = 1; i <= in.size(); ++i) {
    const ClipVertex& vert = in[i % in.size()];  // inlist[n] = inlist[0]
    const float dp = plane_distance(vert.pos_clip, plane);
    if (is_inf_or_nan(dp)) return false;
    bool different_sign;
    if (dp_prev >= 0.0f) {
      if (out.size() >= kMaxClippedVertices) return false;
      out.push_back(*prev);
      different_sign = dp < 0.0f;
    } else {
      different_sign = !(dp < 0.0f);
    }
    if (different_sign) {
      if (out.size() >= kMaxClippedVertices) return false;
      out.push_back(intersect(*prev, dp_prev, vert, dp, viewport));
    }
    prev = &vert;
    dp_prev = dp;
  }
  return true;
}

// The passes over the planes of `mask`, in increasing bit order, starting from the triangle;
// nullptr when the primitive must be discarded, else the polygon (one of the two buffers).
const Polygon* clip_polygon(const std::array<ClipVertex, 3>& triangle, uint32_t mask, const ViewportTransform& viewport,
                            Polygon (&buffers)[2]) {
  Polygon* polygon = &buffers[0];
  for (const ClipVertex& v : triangle) polygon->push_back(v);
  for (; mask != 0 && polygon->size() >= 3; mask &= mask - 1) {
    if (polygon->size() >= kMaxClippedVertices) return nullptr;
    Polygon* next = polygon == &buffers[0] ? &buffers[1] : &buffers[0];
    if (!clip_against(*polygon, uint32_t(std::countr_zero(mask)), viewport, *next)) return nullptr;
    polygon = next;
  }
  return polygon;
}

// emit_poly with flatshade_first: (p0, p[k-1], p[k]); at most kMaxClippedVertices - 2 triangles.
void emit_fan(const Polygon& polygon, ClippedTriangles& result) {
  for (size_t k = 2; k < polygon.size(); ++k) result.triangles.emplace_back(polygon[0], polygon[k - 1], polygon[k]);
}

}  // namespace

ClippedTriangles clip_triangle(const std::array<ClipVertex, 3>& triangle, const ViewportTransform& viewport,
                               uint32_t inside_planes) {
  ClippedTriangles result;
  const uint32_t union_mask = triangle[0].clip_mask | triangle[1].clip_mask | triangle[2].clip_mask;
  if (union_mask == 0) {       // passed unchanged (§1.5)
    if (inside_planes != 0) {  // WorkSkips::clip_only_when_needed off: the clipper returns it unchanged
      Polygon buffers[2];
      const Polygon* same = clip_polygon(triangle, inside_planes, viewport, buffers);
      if (same) {
        emit_fan(*same, result);
        return result;
      }
    }
    result.triangles.push_back(triangle);
    return result;
  }
  if ((triangle[0].clip_mask & triangle[1].clip_mask & triangle[2].clip_mask) != 0) {
    result.fate = ClipFate::Outside;
    return result;
  }
  Polygon buffers[2];
  const Polygon* polygon = clip_polygon(triangle, union_mask, viewport, buffers);
  if (!polygon) {
    result.fate = ClipFate::Discarded;
    return result;
  }
  result.fate = ClipFate::Clipped;
  emit_fan(*polygon, result);
  return result;
}

}  // namespace rastercmp::cpu
