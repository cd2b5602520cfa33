// Triangle clipping, draw_pipe_clip.c clip_tri / do_clip_tri (docs/lavapipe-rules.md §1.5, §1.6; steps 6, 7).
// Sutherland–Hodgman over the planes of the union of the vertex masks, in increasing bit order;
// each new vertex starts from the vertex nearer the plane; a non-finite plane distance drops the
// whole primitive; the polygon is fanned as (p0, p[k-1], p[k]) (provoking vertex first).
// Not modelled: user clip planes, clip distances, the guard band (never used with our targets).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>

#include "cpu_raster/exact/clip_vertex.hpp"

namespace rastercmp::cpu {

// draw_pipe_clip.c MAX_CLIPPED_VERTICES with 8 user planes: a longer polygon is dropped.
inline constexpr size_t kMaxClippedVertices = 2 * (6 + 8) + 1;

// The triangles a clipped polygon is fanned into, held in place: at most kMaxClippedVertices - 2
// (the polygon's limit). A std::vector cost an allocation per triangle through the clipper: every
// triangle of the exact path, and each clipped one of the fast path (perspective: 762 allocations
// a render, 152 without them; docs/performance.md, session 16). The triangles past size() are
// left unformed (a default-constructed array would be cleared first).
class ClippedFan {
 public:
  using Triangle = std::array<ClipVertex, 3>;
  static constexpr size_t kCapacity = kMaxClippedVertices - 2;

  ClippedFan() {}
  ClippedFan(const ClippedFan& other) { *this = other; }
  ClippedFan& operator=(const ClippedFan& other) {
    if (&other == this) return *this;
    count_ = 0;
    for (const Triangle& t : other) push_back(t);
    return *this;
  }

  size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  const Triangle& operator[](size_t i) const { return items_[i]; }
  const Triangle* begin() const { return items_; }
  const Triangle* end() const { return items_ + count_; }
  // The clipper keeps to kCapacity. Built in place from its corners (a Triangle formed first and
  // then copied stalled on the copy's loads).
  void push_back(const Triangle& t) { new (&items_[count_++]) Triangle(t); }
  void push_back(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c) {
    new (&items_[count_++]) Triangle{a, b, c};
  }

 private:
  union {
    Triangle items_[kCapacity];
  };
  size_t count_ = 0;
};
static_assert(std::is_trivially_copyable_v<ClippedFan::Triangle> && std::is_trivially_destructible_v<ClipVertex>);

enum class ClipFate {
  Inside,     // OR of the masks is 0: passed unchanged
  Clipped,    // the polygon was cut; `triangles` holds the fan (possibly empty)
  Outside,    // AND of the masks is non-zero: trivially rejected
  Discarded,  // an Inf/NaN plane distance, or more vertices than the clipper holds
};

struct ClippedTriangles {
  ClipFate fate = ClipFate::Inside;
  ClippedFan triangles;  // what goes on to set-up, in emit order
};

// `inside_planes`: planes to clip a triangle wholly inside against anyway (WorkSkips::
// clip_only_when_needed off; 0: pass it unchanged, as lavapipe does). Every plane distance of such
// a triangle is >= 0, so the clipper returns it unchanged (fate stays Inside). A non-finite distance,
// which the clip test lets through (w = +Inf; |x| + w overflowing; z Inf or NaN without depth
// clipping), would make do_clip_tri discard it although lavapipe never clips it: it is then passed
// unchanged too. Forcing the clipper does not make a draw "pipelined" (§2.6's float cull).
ClippedTriangles clip_triangle(const std::array<ClipVertex, 3>& triangle, const ViewportTransform& viewport,
                               uint32_t inside_planes = 0);

}  // namespace rastercmp::cpu
