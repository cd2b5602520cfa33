#include "cpu_raster/methods/clip_polygon_weiler_atherton.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>

namespace rastercmp::methods {

namespace {

struct Crossing {
  size_t subject_edge = 0, clip_edge = 0;
  double t = 0, u = 0;  // along the subject edge, along the clip edge
  Vec2 point;
  bool entering = false;  // the subject boundary enters the clip region here
};

// One vertex list entry: a polygon vertex or a crossing (twin: the same crossing in the other list).
struct Node {
  Vec2 point;
  size_t next = 0;
  std::optional<size_t> twin;
};

enum class Contact { Apart, Proper, Degenerate };

bool same_strict_sign(double a, double b) { return (a > 0 && b > 0) || (a < 0 && b < 0); }

bool collinear_overlap(Vec2 a0, Vec2 a1, Vec2 b0, Vec2 b1) {
  const Vec2 d = a1 - a0;
  const double s0 = dot(b0 - a0, d), s1 = dot(b1 - a0, d), len = dot(d, d);
  return std::max(s0, s1) >= 0 && std::min(s0, s1) <= len;
}

Contact classify(Vec2 a0, Vec2 a1, Vec2 b0, Vec2 b1, Crossing& crossing) {
  const double d_b0 = cross(a1 - a0, b0 - a0), d_b1 = cross(a1 - a0, b1 - a0);
  const double d_a0 = cross(b1 - b0, a0 - b0), d_a1 = cross(b1 - b0, a1 - b0);
  if (same_strict_sign(d_b0, d_b1) || same_strict_sign(d_a0, d_a1)) return Contact::Apart;
  if (d_b0 == 0 && d_b1 == 0) return collinear_overlap(a0, a1, b0, b1) ? Contact::Degenerate : Contact::Apart;
  if (d_b0 == 0 || d_b1 == 0 || d_a0 == 0 || d_a1 == 0) return Contact::Degenerate;
  crossing.t = d_a0 / (d_a0 - d_a1);
  crossing.u = d_b0 / (d_b0 - d_b1);
  crossing.point = lerp(a0, a1, crossing.t);
  // Entering when the subject edge points to the left (the inside) of the counter-clockwise clip edge.
  crossing.entering = cross(b1 - b0, a1 - a0) > 0;
  return Contact::Proper;
}

Polygon2 counter_clockwise(const Polygon2& polygon, const char* name) {
  const double area = polygon.size() < 3 ? 0 : signed_area(polygon);
  if (area == 0) {
    throw std::invalid_argument(std::string("clip_polygon_weiler_atherton: ") + name +
                                " needs at least 3 vertices and non-zero area");
  }
  Polygon2 out = polygon;
  if (area < 0) std::reverse(out.begin(), out.end());
  return out;
}

// Appends one vertex list: vertex i, then the crossings on edge i sorted by `along`; returns the
// node index of each crossing.
template <typename EdgeOf, typename Along>
std::vector<size_t> append_list(std::vector<Node>& nodes, const Polygon2& polygon,
                                const std::vector<Crossing>& crossings, EdgeOf edge_of, Along along) {
  std::vector<size_t> order(crossings.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const size_t ea = edge_of(crossings[a]), eb = edge_of(crossings[b]);
    return ea != eb ? ea < eb : along(crossings[a]) < along(crossings[b]);
  });
  std::vector<size_t> node_of(crossings.size());
  const size_t first = nodes.size();
  size_t k = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    nodes.push_back({polygon[i], 0, std::nullopt});
    for (; k < order.size() && edge_of(crossings[order[k]]) == i; ++k) {
      node_of[order[k]] = nodes.size();
      nodes.push_back({crossings[order[k]].point, 0, std::nullopt});
    }
  }
  for (size_t n = first; n < nodes.size(); ++n) nodes[n].next = n + 1 < nodes.size() ? n + 1 : first;
  return node_of;
}

// Follows one output loop from an entering crossing; false if it does not close (float trouble).
bool trace_loop(const std::vector<Node>& nodes, size_t start, std::vector<bool>& visited, Polygon2& loop) {
  size_t current = start;
  for (size_t steps = 0; steps <= 2 * nodes.size(); ++steps) {
    loop.push_back(nodes[current].point);
    visited[current] = visited[*nodes[current].twin] = true;
    current = nodes[current].next;
    while (!nodes[current].twin) {
      loop.push_back(nodes[current].point);
      current = nodes[current].next;
    }
    current = *nodes[current].twin;  // switch lists at the next crossing
    if (current == start) return true;
  }
  return false;
}

std::vector<Crossing> find_crossings(const Polygon2& subject, const Polygon2& clip, bool& degenerate) {
  std::vector<Crossing> crossings;
  for (size_t i = 0; i < subject.size(); ++i) {
    for (size_t j = 0; j < clip.size(); ++j) {
      Crossing c;
      c.subject_edge = i;
      c.clip_edge = j;
      const Contact contact =
          classify(subject[i], subject[(i + 1) % subject.size()], clip[j], clip[(j + 1) % clip.size()], c);
      if (contact == Contact::Degenerate) degenerate = true;
      if (contact == Contact::Proper) crossings.push_back(c);
    }
  }
  return crossings;
}

}  // namespace

WeilerAthertonResult clip_polygon_weiler_atherton(const Polygon2& subject_in, const Polygon2& clip_in) {
  const Polygon2 subject = counter_clockwise(subject_in, "subject");
  const Polygon2 clip = counter_clockwise(clip_in, "clip");
  WeilerAthertonResult result;
  const std::vector<Crossing> crossings = find_crossings(subject, clip, result.degenerate);
  result.crossings = crossings.size();
  if (result.degenerate) return result;
  if (crossings.empty()) {
    if (inside_even_odd(clip, subject[0]))
      result.polygons.push_back(subject);
    else if (inside_even_odd(subject, clip[0]))
      result.polygons.push_back(clip);
    return result;
  }
  std::vector<Node> nodes;
  const std::vector<size_t> subject_node = append_list(
      nodes, subject, crossings, [](const Crossing& c) { return c.subject_edge; },
      [](const Crossing& c) { return c.t; });
  const std::vector<size_t> clip_node = append_list(
      nodes, clip, crossings, [](const Crossing& c) { return c.clip_edge; }, [](const Crossing& c) { return c.u; });
  for (size_t k = 0; k < crossings.size(); ++k) {
    nodes[subject_node[k]].twin = clip_node[k];
    nodes[clip_node[k]].twin = subject_node[k];
  }
  std::vector<bool> visited(nodes.size(), false);
  for (size_t k = 0; k < crossings.size(); ++k) {
    if (!crossings[k].entering || visited[subject_node[k]]) continue;
    Polygon2 loop;
    if (!trace_loop(nodes, subject_node[k], visited, loop)) {
      result.degenerate = true;
      result.polygons.clear();
      return result;
    }
    result.polygons.push_back(std::move(loop));
  }
  return result;
}

}  // namespace rastercmp::methods
