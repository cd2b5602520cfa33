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

// At most N values held in place, for the clipper's polygons and fans: a std::vector cost
// allocations for every triangle through the clipper (several per plane for the polygon, session
// 15; one for the fan: every triangle of the exact path, each clipped one of the fast path, whose
// perspective render made 762 allocations and now 152; docs/performance-log.md, 608f032). The
// values past size() are left unformed (a default-constructed array would be cleared first); the
// clipper keeps to N.
template <class T, size_t N>
class InPlaceList {
 public:
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

  InPlaceList() {}
  InPlaceList(const InPlaceList& other) { *this = other; }
  InPlaceList& operator=(const InPlaceList& other) {
    if (&other == this) return *this;
    count_ = 0;
    for (const T& v : other) push_back(v);
    return *this;
  }

  size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  const T& operator[](size_t i) const { return items_[i]; }
  const T* begin() const { return items_; }
  const T* end() const { return items_ + count_; }
  void clear() { count_ = 0; }
  void push_back(const T& v) { new (&items_[count_++]) T(v); }
  // Built in place from its parts: a T formed first and then copied stalled on the copy's loads
  // (a fan's triangle from three polygon vertices: 64 ns a clipped triangle against 90).
  template <class... Parts>
  void emplace_back(const Parts&... parts) {
    new (&items_[count_++]) T{parts...};
  }

 private:
  union {
    T items_[N];
  };
  size_t count_ = 0;
};

// The triangles a clipped polygon is fanned into: at most the polygon's limit less two.
using ClippedFan = InPlaceList<std::array<ClipVertex, 3>, kMaxClippedVertices - 2>;

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
