#include "cpu_raster/spec/shared_edges.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <map>
#include <utility>

namespace rastercmp::cpu::spec {
namespace {

using PointBits = std::pair<uint32_t, uint32_t>;  // window x, y as float bits

PointBits point_bits(const WindowVertex& v) { return {std::bit_cast<uint32_t>(v.x), std::bit_cast<uint32_t>(v.y)}; }

struct EdgeRef {
  size_t triangle = 0;
  int edge = 0;
  int side = 0;  // +1 / -1: which side of the canonical low→high direction the triangle lies on
};

bool same_clip_vertex(const glm::vec4& a, const glm::vec4& b) {
  for (int k = 0; k < 4; ++k)
    if (std::bit_cast<uint32_t>(a[k]) != std::bit_cast<uint32_t>(b[k])) return false;
  return true;
}

// The unclipped triangles have two bit-identical clip-space vertices in common.
bool sources_share_edge(const SpecTriangle& a, const SpecTriangle& b) {
  int common = 0;
  for (const glm::vec4& p : a.source_clip)
    if (std::any_of(b.source_clip.begin(), b.source_clip.end(),
                    [&](const glm::vec4& q) { return same_clip_vertex(p, q); }))
      ++common;
  return common >= 2;
}

bool same_source(const SpecTriangle& a, const SpecTriangle& b) {
  return (a.draw_index == b.draw_index && a.primitive_index == b.primitive_index) || sources_share_edge(a, b);
}

}  // namespace

std::vector<SharedEdge> find_shared_edges(const std::vector<SpecTriangle>& triangles) {
  std::map<std::pair<PointBits, PointBits>, std::vector<EdgeRef>> by_endpoints;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const SpecTriangle& tri = triangles[t];
    if (tri.facing != Gate::Certain || tri.snapped.area_sign == 0) continue;
    for (int e = 0; e < 3; ++e) {
      const PointBits from = point_bits(tri.window[size_t(e)]), to = point_bits(tri.window[size_t((e + 1) % 3)]);
      if (from == to) continue;
      const bool forward = from < to;
      // The third vertex lies left of from→to (y up) when cross(v1-v0, v2-v0) > 0, i.e. a < 0.
      const int cross_sign = -tri.snapped.area_sign;
      by_endpoints[forward ? std::pair{from, to} : std::pair{to, from}].push_back(
          {t, e, forward ? cross_sign : -cross_sign});
    }
  }
  std::vector<SharedEdge> shared;
  for (const auto& [endpoints, refs] : by_endpoints)
    for (size_t i = 0; i < refs.size(); ++i)
      for (size_t j = i + 1; j < refs.size(); ++j) {
        const EdgeRef &a = refs[i], &b = refs[j];
        if (a.side == b.side || !same_source(triangles[a.triangle], triangles[b.triangle])) continue;
        shared.push_back({a.triangle, b.triangle, a.edge, b.edge});
      }
  return shared;
}

bool promoted(const std::vector<SpecTriangle>& triangles, const SharedEdge& shared, const ToleranceBox& box) {
  const auto inside_others = [&](size_t t, int shared_edge) {
    for (int e = 0; e < 3; ++e)
      if (e != shared_edge && !box_inside_edge(triangles[t].snapped, e, box)) return false;
    return true;
  };
  return inside_others(shared.first, shared.first_edge) && inside_others(shared.second, shared.second_edge);
}

}  // namespace rastercmp::cpu::spec
