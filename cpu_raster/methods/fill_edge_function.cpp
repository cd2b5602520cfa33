#include "cpu_raster/methods/fill_edge_function.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rastercmp::methods {

float edge_function(Vec2f a, Vec2f b, Vec2f p) {
  const float lhs = (b.x - a.x) * (p.y - a.y);
  const float rhs = (b.y - a.y) * (p.x - a.x);
  return lhs - rhs;
}

namespace {

struct Edge {
  Vec2f a, b;
  bool inclusive = true;  // a sample with E == 0 is covered
};

bool is_top_left(Vec2f a, Vec2f b) {
  const float de_dx = -(b.y - a.y), de_dy = b.x - a.x;
  return de_dx > 0 || (de_dx == 0 && de_dy > 0);
}

bool covers(const std::array<Edge, 3>& edges, Vec2f centre) {
  for (const Edge& e : edges) {
    const float value = edge_function(e.a, e.b, centre);
    if (value < 0 || (value == 0 && !e.inclusive)) return false;
  }
  return true;
}

int32_t floor_to_pixel(float v) {
  return int32_t(std::clamp(std::floor(double(v)), -double(1 << 30), double(1 << 30)));
}

}  // namespace

std::vector<Span> fill_triangle_edge_function(const std::array<Vec2f, 3>& pos_window, EdgeTieRule tie_rule,
                                              const PixelBounds& bounds) {
  SpanBuilder spans;
  Vec2f v0 = pos_window[0], v1 = pos_window[1], v2 = pos_window[2];
  const float area2 = edge_function(v0, v1, v2);
  if (area2 == 0 || std::isnan(area2)) return spans.take();
  if (area2 < 0) std::swap(v1, v2);  // interior: E > 0 on every edge
  std::array<Edge, 3> edges{Edge{v0, v1}, Edge{v1, v2}, Edge{v2, v0}};
  if (tie_rule == EdgeTieRule::TopLeft) {
    for (Edge& e : edges) e.inclusive = is_top_left(e.a, e.b);
  }
  const float x_lo = std::min({v0.x, v1.x, v2.x}), x_hi = std::max({v0.x, v1.x, v2.x});
  const float y_lo = std::min({v0.y, v1.y, v2.y}), y_hi = std::max({v0.y, v1.y, v2.y});
  const int32_t x_begin = std::max(floor_to_pixel(x_lo), bounds.x_min);
  const int32_t x_end = std::min(floor_to_pixel(x_hi) + 1, bounds.x_max);
  const int32_t y_begin = std::max(floor_to_pixel(y_lo), bounds.y_min);
  const int32_t y_end = std::min(floor_to_pixel(y_hi) + 1, bounds.y_max);
  for (int32_t y = y_begin; y < y_end; ++y) {
    int32_t run_begin = x_begin;
    for (int32_t x = x_begin; x <= x_end; ++x) {
      const bool in = x < x_end && covers(edges, {float(x) + 0.5f, float(y) + 0.5f});
      if (!in) {
        spans.add(y, run_begin, x);
        run_begin = x + 1;
      }
    }
  }
  return spans.take();
}

}  // namespace rastercmp::methods
