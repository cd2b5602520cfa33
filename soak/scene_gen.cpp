#include "soak/scene_gen.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "model/errors.hpp"
#include "model/scene_io.hpp"
#include "soak/rng.hpp"
#include "soak/scene_write.hpp"

namespace rastercmp::soak {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Gen {
  Rng& r;
  Scene& s;

  // Framebuffer pixels (x, y), a depth value and the wanted clip w → clip space, through the
  // effective viewport (the inverse viewport transform of docs/scene-format.md "pixels").
  glm::vec4 px(double x, double y, double depth, double w = 1) const {
    const Viewport v = s.effective_viewport();
    const double ox = v.x + v.width / 2.0, oy = v.y + v.height / 2.0;
    const double pz = double(v.max_depth) - double(v.min_depth);
    const double zc = pz != 0 ? (depth - v.min_depth) / pz : depth;
    return {float(w * (x - ox) / (v.width / 2.0)), float(w * (y - oy) / (v.height / 2.0)), float(w * zc), float(w)};
  }

  static double grid(double v, double denom = 256) { return std::round(v * denom) / denom; }
  // A coordinate on the 1/256 grid, on whole or half pixels a third of the time each.
  double coord(double lo, double hi) {
    const double v = r.uniform(lo, hi);
    switch (r.range(0, 2)) {
      case 0: return std::round(v);
      case 1: return std::floor(v) + 0.5;
      default: return grid(v);
    }
  }
  double depth() { return r.chance(0.5) ? grid(r.unit()) : r.unit(); }
  double log_uniform(double lo, double hi) { return std::exp(r.uniform(std::log(lo), std::log(hi))); }

  void frame(std::initializer_list<uint32_t> sides = {16, 17, 24, 32, 33, 48, 64}) {
    s.width = r.pick(sides);
    s.height = r.chance(0.7) ? s.width : r.pick(sides);
  }
  void depth_setup() {
    s.depth_format = r.pick({DepthFormat::D32Sfloat, DepthFormat::D32Sfloat, DepthFormat::X8D24Unorm,
                             DepthFormat::D16Unorm, DepthFormat::None});
    if (r.chance(0.3)) s.depth_clear = float(r.pick({0.0, 0.5, 1.0, grid(r.unit())}));
  }

  CompareOp any_compare() {
    return r.pick({CompareOp::Never, CompareOp::Less, CompareOp::Equal, CompareOp::LessOrEqual, CompareOp::Greater,
                   CompareOp::NotEqual, CompareOp::GreaterOrEqual, CompareOp::Always});
  }
  void cull_state(RasterState& st) {
    if (r.chance(0.5)) st.cull_mode = r.pick({CullMode::None, CullMode::Front, CullMode::Back, CullMode::FrontAndBack});
    if (r.chance(0.5)) st.front_face = FrontFace::Clockwise;
  }
  void depth_state(RasterState& st) {
    if (r.chance(0.5)) st.depth.compare_op = any_compare();
    if (r.chance(0.15)) st.depth.test_enable = false;
    if (r.chance(0.2)) st.depth.write_enable = false;
  }
  void bias_state(RasterState& st) {
    st.depth_bias.enable = true;
    st.depth_bias.constant_factor = float(r.pick({0.0, 1.0, -1.0, 2.5, 100.0, -3000.0, double(r.range(-64, 64))}));
    st.depth_bias.slope_factor = float(r.pick({0.0, 0.5, 1.0, -2.0, grid(r.uniform(-8, 8), 16)}));
    st.depth_bias.clamp = float(r.pick({0.0, 0.0, 1e-4, -1e-4, 0.01, -0.5}));
  }
  void line_state(RasterState& st) {
    // rectangular_smooth, point_list and polygon modes line and point are NotSupported by the CPU
    // lavapipe profile (cpu_raster/exact/profile_support.cpp): generating them would only skip.
    st.line_mode = r.pick({LineMode::Default, LineMode::Rectangular, LineMode::Bresenham});
    st.line_width = float(r.pick({1.0, 1.0, 1.5, 2.0, 3.0, 4.75, 8.0, 17.0}));
  }

  Draw& add(Topology topology, std::vector<glm::vec4> positions, std::vector<uint32_t> indices = {}) {
    Draw d;
    d.topology = topology;
    d.positions_clip = std::move(positions);
    d.indices = std::move(indices);
    s.draws.push_back(std::move(d));
    return s.draws.back();
  }

  // A triangle of random pixel vertices over the framebuffer and a margin.
  std::vector<glm::vec4> triangle(double margin = 0.25) {
    std::vector<glm::vec4> v;
    for (int i = 0; i < 3; ++i)
      v.push_back(px(coord(-margin * s.width, (1 + margin) * s.width),
                     coord(-margin * s.height, (1 + margin) * s.height), depth()));
    return v;
  }
};

// Shared edges and ties on the 1/256 grid: a mesh of grid cells, each split on a random diagonal,
// drawn as one indexed list (or twice, the second with an equal-ish compare).
void gen_tie(Gen& g) {
  g.frame();
  g.depth_setup();
  const int cols = int(g.r.range(2, 5)), rows = int(g.r.range(2, 5));
  std::vector<glm::vec4> p;
  const double step = g.r.pick({1.0, 0.5, 1.0 / 256});
  for (int y = 0; y <= rows; ++y)
    for (int x = 0; x <= cols; ++x) {
      const double fx = double(x) * g.s.width / cols, fy = double(y) * g.s.height / rows;
      const double jx = g.r.chance(0.5) ? double(g.r.range(-3, 3)) * step : 0;
      const double jy = g.r.chance(0.5) ? double(g.r.range(-3, 3)) * step : 0;
      p.push_back(g.px(Gen::grid(fx + jx), Gen::grid(fy + jy), g.depth()));
    }
  std::vector<uint32_t> idx;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) {
      const uint32_t a = uint32_t(y * (cols + 1) + x), b = a + 1, c = a + uint32_t(cols + 1), d = c + 1;
      if (g.r.chance(0.5))
        idx.insert(idx.end(), {a, b, d, a, d, c});
      else
        idx.insert(idx.end(), {a, b, c, b, d, c});
    }
  Draw& d = g.add(Topology::TriangleList, p, idx);
  g.cull_state(d.state);
  if (g.r.chance(0.4)) {
    Draw again = g.s.draws.back();
    again.state.depth.compare_op = g.r.pick({CompareOp::Equal, CompareOp::LessOrEqual, CompareOp::GreaterOrEqual});
    g.s.draws.push_back(again);
  }
}

// Fans and strips around a grid point, sharing every inner edge.
void gen_fan(Gen& g) {
  g.frame();
  g.depth_setup();
  const int draws = int(g.r.range(1, 3));
  for (int k = 0; k < draws; ++k) {
    const double cx = g.coord(0, g.s.width), cy = g.coord(0, g.s.height);
    const double radius = g.r.uniform(2, 1.5 * std::max(g.s.width, g.s.height));
    const int rim = int(g.r.range(3, 12));
    const double phase = g.r.uniform(0, 2 * kPi);
    const double cz = g.depth();
    std::vector<glm::vec4> ring;
    for (int i = 0; i <= rim; ++i) {
      const double a = phase + 2 * kPi * (i % rim) / rim;
      ring.push_back(g.px(Gen::grid(cx + radius * std::cos(a)), Gen::grid(cy + radius * std::sin(a)), g.depth()));
    }
    const glm::vec4 center = g.px(cx, cy, cz);
    const int shape = int(g.r.range(0, 2));
    Draw* d = nullptr;
    if (shape == 0) {
      std::vector<glm::vec4> p{center};
      p.insert(p.end(), ring.begin(), ring.end());
      d = &g.add(Topology::TriangleFan, p);
    } else if (shape == 1) {  // the same fan as an indexed list
      std::vector<glm::vec4> p{center};
      p.insert(p.end(), ring.begin(), ring.end());
      std::vector<uint32_t> idx;
      for (uint32_t i = 1; i <= uint32_t(rim); ++i) idx.insert(idx.end(), {0, i, i + 1});
      d = &g.add(Topology::TriangleList, p, idx);
    } else {  // a strip zigzagging between the ring and a smaller ring
      std::vector<glm::vec4> p;
      for (int i = 0; i <= rim; ++i) {
        const double a = phase + 2 * kPi * (i % rim) / rim;
        p.push_back(ring[size_t(i)]);
        p.push_back(g.px(Gen::grid(cx + 0.4 * radius * std::cos(a)), Gen::grid(cy + 0.4 * radius * std::sin(a)), cz));
      }
      d = &g.add(Topology::TriangleStrip, p);
    }
    g.cull_state(d->state);
    g.depth_state(d->state);
  }
}

// Perspective: per-vertex clip w from 0.01 to 100 over the same pixels.
void gen_perspective(Gen& g) {
  g.frame();
  g.depth_setup();
  const int draws = int(g.r.range(1, 4));
  for (int k = 0; k < draws; ++k) {
    const int prims = int(g.r.range(1, 6));
    const bool strip = g.r.chance(0.4);
    std::vector<glm::vec4> p;
    const int verts = strip ? prims + 2 : 3 * prims;
    for (int i = 0; i < verts; ++i)
      p.push_back(g.px(g.coord(-0.5 * g.s.width, 1.5 * g.s.width), g.coord(-0.5 * g.s.height, 1.5 * g.s.height),
                       g.depth(), g.log_uniform(0.01, 100)));
    Draw& d = g.add(strip ? Topology::TriangleStrip : Topology::TriangleList, p);
    g.cull_state(d.state);
    g.depth_state(d.state);
  }
}

// Clipping: vertices behind the eye (w < 0), beyond near and far, and far out in the guard band.
void gen_clip(Gen& g) {
  g.frame();
  g.depth_setup();
  if (g.r.chance(0.3)) {
    Viewport v = g.s.effective_viewport();
    v.min_depth = float(Gen::grid(g.r.unit()));
    v.max_depth = float(Gen::grid(g.r.unit()));
    g.s.viewport = v;
  }
  const int draws = int(g.r.range(1, 3));
  for (int k = 0; k < draws; ++k) {
    std::vector<glm::vec4> p;
    const int prims = int(g.r.range(1, 4));
    for (int i = 0; i < 3 * prims; ++i) {
      double w = g.r.pick({1.0, g.r.uniform(0.1, 4), g.r.uniform(-2, -0.01), 1e-3});
      double x = g.r.uniform(-3, 3) * std::abs(w), y = g.r.uniform(-3, 3) * std::abs(w);
      const double z = g.r.pick({g.r.uniform(0, 1), g.r.uniform(-1.5, 0), g.r.uniform(1, 2.5), 0.0, 1.0}) * w;
      if (g.r.chance(0.2)) x = (g.r.chance(0.5) ? 1 : -1) * g.log_uniform(1e3, 1e7) * std::abs(w);
      if (g.r.chance(0.1)) y = (g.r.chance(0.5) ? 1 : -1) * g.log_uniform(1e3, 1e7) * std::abs(w);
      p.push_back({float(x), float(y), float(z), float(w)});
    }
    Draw& d = g.add(Topology::TriangleList, p);
    if (g.r.chance(0.4)) d.state.depth_clamp = true;
    if (g.r.chance(0.3)) d.state.depth_clip = g.r.chance(0.5);
    g.cull_state(d.state);
    g.depth_state(d.state);
  }
}

// Depth: every format and compare op, depth ranges in either order, bias and its clamp, and
// planes far from the origin (depth near 1 with tiny slopes).
void gen_depth(Gen& g) {
  g.frame();
  g.depth_setup();
  if (g.s.depth_format == DepthFormat::None && g.r.chance(0.7)) g.s.depth_format = DepthFormat::D16Unorm;
  if (g.r.chance(0.4)) {
    Viewport v = g.s.effective_viewport();
    v.min_depth = float(g.r.pick({0.0, 1.0, 0.25, Gen::grid(g.r.unit())}));
    v.max_depth = float(g.r.pick({0.0, 1.0, 0.75, Gen::grid(g.r.unit())}));
    g.s.viewport = v;
  }
  const int draws = int(g.r.range(2, 6));
  for (int k = 0; k < draws; ++k) {
    std::vector<glm::vec4> p = g.triangle(0.5);
    if (g.r.chance(0.3)) {  // a far plane: depth 1 - tiny, slopes of a few ulps
      const double base = 1 - g.log_uniform(1e-7, 1e-3);
      for (glm::vec4& v : p) v.z = float(base + g.r.uniform(-1e-7, 1e-7));
    }
    Draw& d = g.add(Topology::TriangleList, p);
    d.state.depth.compare_op = g.any_compare();
    if (g.r.chance(0.2)) d.state.depth.write_enable = false;
    if (g.r.chance(0.1)) d.state.depth.test_enable = false;
    if (g.r.chance(0.5)) g.bias_state(d.state);
    if (g.r.chance(0.2)) d.state.depth_clamp = true;
  }
}

// Odd viewports (fractional, flipped, tiny, partly outside) and scissors (empty, offset, past the edge).
void gen_viewport(Gen& g) {
  g.frame();
  g.depth_setup();
  const double W = g.s.width, H = g.s.height;
  Viewport v;
  v.x = float(g.r.pick({0.0, Gen::grid(g.r.uniform(-W, W)), Gen::grid(g.r.uniform(0, W), 2)}));
  v.y = float(g.r.pick({0.0, Gen::grid(g.r.uniform(-H, H)), Gen::grid(g.r.uniform(0, H), 2)}));
  v.width = float(g.r.pick({W, Gen::grid(g.r.uniform(0.5, 2 * W)), Gen::grid(g.r.uniform(0.25, 4)), 1.0}));
  v.height = float(g.r.pick({H, Gen::grid(g.r.uniform(0.5, 2 * H)), Gen::grid(g.r.uniform(0.25, 4)), 1.0}));
  if (v.width <= 0) v.width = 1;
  if (v.height <= 0) v.height = 1;
  if (g.r.chance(0.4)) v.height = -v.height;
  if (g.r.chance(0.3)) std::swap(v.min_depth, v.max_depth);
  g.s.viewport = v;
  if (g.r.chance(0.6)) {
    Rect2D sc;
    sc.x = int32_t(g.r.range(0, int64_t(W)));
    sc.y = int32_t(g.r.range(0, int64_t(H)));
    sc.width = uint32_t(g.r.pick({int64_t(0), g.r.range(1, int64_t(W)), int64_t(1), int64_t(2 * W)}));
    sc.height = uint32_t(g.r.pick({int64_t(0), g.r.range(1, int64_t(H)), int64_t(1), int64_t(2 * H)}));
    g.s.scissor = sc;
  }
  const int draws = int(g.r.range(1, 3));
  for (int k = 0; k < draws; ++k) {
    std::vector<glm::vec4> p;
    for (int i = 0, n = 3 * int(g.r.range(1, 3)); i < n; ++i)
      p.push_back({float(Gen::grid(g.r.uniform(-1.5, 1.5))), float(Gen::grid(g.r.uniform(-1.5, 1.5))),
                   float(g.r.unit()), 1.0f});
    Draw& d = g.add(Topology::TriangleList, p);
    g.cull_state(d.state);
  }
}

// Slivers: needle triangles a 1/256 pixel wide, sub-pixel triangles, exactly collinear ones, and
// long thin triangles whose vertices lie far from the origin.
void gen_sliver(Gen& g) {
  g.frame();
  g.depth_setup();
  std::vector<glm::vec4> p;
  const int prims = int(g.r.range(2, 10));
  for (int i = 0; i < prims; ++i) {
    const double ax = g.coord(0, g.s.width), ay = g.coord(0, g.s.height);
    double bx = g.coord(0, g.s.width), by = g.coord(0, g.s.height);
    const int kind = int(g.r.range(0, 3));
    if (kind == 3) {  // far from the origin: long, crossing the framebuffer
      const double far = g.log_uniform(1e3, 1e6);
      const double a = g.r.uniform(0, 2 * kPi);
      bx = ax + far * std::cos(a);
      by = ay + far * std::sin(a);
    }
    const double t = g.r.unit();
    double off = g.r.pick({0.0, 1.0 / 256, 2.0 / 256, 1.0 / 16, 0.5});
    if (kind == 1) {  // sub-pixel
      bx = ax + Gen::grid(g.r.uniform(-1, 1));
      by = ay + Gen::grid(g.r.uniform(-1, 1));
      off = Gen::grid(g.r.uniform(-1, 1));
    }
    const double len = std::max(1e-9, std::hypot(bx - ax, by - ay));
    const double cx = ax + t * (bx - ax) - off * (by - ay) / len, cy = ay + t * (by - ay) + off * (bx - ax) / len;
    p.push_back(g.px(ax, ay, g.depth()));
    p.push_back(g.px(Gen::grid(bx), Gen::grid(by), g.depth()));
    p.push_back(g.px(kind == 2 ? ax + 0.5 * (bx - ax) : Gen::grid(cx), kind == 2 ? ay + 0.5 * (by - ay) : Gen::grid(cy),
                     g.depth()));
  }
  Draw& d = g.add(Topology::TriangleList, p);
  g.cull_state(d.state);
  g.depth_state(d.state);
}

// Magnitudes: denormal and tiny coordinates, huge w with the same NDC, huge w = 1 triangles.
void gen_magnitude(Gen& g) {
  g.frame();
  g.depth_setup();
  const int draws = int(g.r.range(1, 3));
  for (int k = 0; k < draws; ++k) {
    std::vector<glm::vec4> p = g.triangle(0.5);
    const int kind = int(g.r.range(0, 3));
    if (kind == 0) {  // tiny: denormal components
      const double tiny = g.r.pick({1e-40, 1e-44, 1e-39, 1e-38, 1e-30});
      for (glm::vec4& v : p) {
        if (g.r.chance(0.4)) v.x = float(tiny * (g.r.chance(0.5) ? 1 : -1));
        if (g.r.chance(0.4)) v.y = float(tiny * (g.r.chance(0.5) ? 1 : -1));
        if (g.r.chance(0.4)) v.z = float(tiny);
      }
    } else if (kind == 1) {  // huge w, same NDC
      const double w = g.log_uniform(1e4, 1e30);
      for (glm::vec4& v : p) v = v * float(w);
    } else if (kind == 2) {  // a huge triangle with w = 1 around the viewport
      const double big = g.log_uniform(1e3, 3e17);
      const float z = float(g.r.unit());
      p = {{float(-big), float(-big), z, 1}, {float(big), float(-big), z, 1}, {0, float(big), z, 1}};
      if (g.r.chance(0.5)) std::swap(p[1], p[2]);
    } else {  // huge and tiny mixed across the vertices of one triangle
      p[0] *= float(g.log_uniform(1, 1e20));
      p[1].x = float(g.log_uniform(1e3, 1e9));
    }
    Draw& d = g.add(Topology::TriangleList, p);
    g.cull_state(d.state);
    g.depth_state(d.state);
  }
}

// Lines: every line mode the lavapipe profile reproduces and widths 1 to 17, lists and strips, some
// exactly horizontal, vertical or diagonal.
void gen_lines(Gen& g) {
  g.frame();
  g.depth_setup();
  const int draws = int(g.r.range(1, 3));
  for (int k = 0; k < draws; ++k) {
    const int kind = int(g.r.range(0, 1));
    std::vector<glm::vec4> p;
    const int n = int(g.r.range(1, 6));
    auto point = [&] { return g.px(g.coord(-4, g.s.width + 4), g.coord(-4, g.s.height + 4), g.depth()); };
    Draw* d = nullptr;
    if (kind == 0 || kind == 1) {  // line list or strip; some exactly horizontal, vertical or diagonal
      const int verts = kind == 0 ? 2 * n : n + 1;
      for (int i = 0; i < verts; ++i) {
        glm::vec4 v = point();
        if (i > 0 && g.r.chance(0.3)) {
          const glm::vec4 prev = p.back();
          const int axis = int(g.r.range(0, 2));
          if (axis == 0) v.y = prev.y;
          if (axis == 1) v.x = prev.x;
          if (axis == 2) v.y = prev.y + (v.x - prev.x);
        }
        p.push_back(v);
      }
      d = &g.add(kind == 0 ? Topology::LineList : Topology::LineStrip, p);
    }
    g.line_state(d->state);
    g.depth_state(d->state);
  }
}

// 4x MSAA: triangles and lines together, with scissors and viewports.
void gen_msaa(Gen& g) {
  g.frame({8, 16, 17, 24, 32});
  g.depth_setup();
  g.s.samples = 4;
  if (g.r.chance(0.3)) {
    Viewport v;
    const double minimum = 0.5;
    v.x = float(Gen::grid(g.r.uniform(0, g.s.width / 2.0), 4));
    v.y = float(Gen::grid(g.r.uniform(0, g.s.height / 2.0), 4));
    v.width = float(std::max(minimum, Gen::grid(g.r.uniform(0.5, g.s.width), 4)));
    v.height = float(std::max(minimum, Gen::grid(g.r.uniform(0.5, g.s.height), 4)));
    g.s.viewport = v;
  }
  if (g.r.chance(0.3)) {
    Rect2D sc;
    sc.x = int32_t(g.r.range(0, g.s.width / 2));
    sc.y = int32_t(g.r.range(0, g.s.height / 2));
    sc.width = uint32_t(g.r.range(0, g.s.width));
    sc.height = uint32_t(g.r.range(0, g.s.height));
    g.s.scissor = sc;
  }
  const int draws = int(g.r.range(1, 4));
  for (int k = 0; k < draws; ++k) {
    if (g.r.chance(0.6)) {
      std::vector<glm::vec4> p;
      for (int i = 0, n = int(g.r.range(1, 4)); i < n; ++i) {
        const auto t = g.triangle();
        p.insert(p.end(), t.begin(), t.end());
      }
      Draw& d = g.add(Topology::TriangleList, p);
      g.cull_state(d.state);
      g.depth_state(d.state);
      if (g.r.chance(0.2)) g.bias_state(d.state);
    } else {
      std::vector<glm::vec4> p = g.triangle(0.1);
      p.pop_back();
      Draw& d = g.add(Topology::LineList, p);
      g.line_state(d.state);
      g.depth_state(d.state);
    }
  }
}

// Denormals (docs/lavapipe-rules.md §7.10, §7.11): tiny and denormal z on some vertices and zero on
// others (the depth plane's gradients underflow), denormal and tiny clear values with every
// compare op, depth bias and clamp on such planes, viewport depth ranges at the denormal boundary,
// and a vertex outside the view volume now and then, so the draw takes the draw pipeline and its
// set-up runs outside the denormal mode.
void gen_denormal(Gen& g) {
  g.frame();
  g.s.depth_format = g.r.pick({DepthFormat::D32Sfloat, DepthFormat::D32Sfloat, DepthFormat::X8D24Unorm,
                               DepthFormat::D16Unorm});
  const auto tiny = [&g] {
    const double magnitude = g.r.chance(0.5) ? g.log_uniform(1e-45, 1.2e-38) : g.log_uniform(1.2e-38, 1e-28);
    return g.r.chance(0.2) ? -magnitude : magnitude;
  };
  if (g.r.chance(0.5)) g.s.depth_clear = float(g.r.chance(0.7) ? std::fabs(tiny()) : g.r.pick({0.0, 1.0}));
  if (g.r.chance(0.25)) {
    Viewport v = g.s.effective_viewport();
    v.min_depth = float(g.r.chance(0.5) ? std::fabs(tiny()) : 0.0);
    v.max_depth = float(g.r.chance(0.5) ? std::fabs(tiny()) : g.r.pick({1.0, 0.5}));
    g.s.viewport = v;
  }
  const int draws = int(g.r.range(1, 4));
  for (int k = 0; k < draws; ++k) {
    const uint32_t triangles = g.r.chance(0.8) ? uint32_t(g.r.range(1, 4)) : uint32_t(g.r.range(5, 60));
    std::vector<glm::vec4> p;
    for (uint32_t t = 0; t < triangles; ++t) {
      std::vector<glm::vec4> tri = g.triangle(g.r.chance(0.4) ? 0.5 : 0.0);
      for (glm::vec4& v : tri) {
        v.z = g.r.chance(0.5) ? 0.0f : float(tiny()) * v.w;
        if (g.r.chance(0.1)) v.x = v.w * float(g.r.pick({1.1, -1.3, 3.0}));  // outside: the pipeline path
      }
      p.insert(p.end(), tri.begin(), tri.end());
    }
    Draw& d = g.add(Topology::TriangleList, p);
    d.state.depth.compare_op = g.any_compare();
    if (g.r.chance(0.15)) d.state.depth.write_enable = false;
    if (g.r.chance(0.5)) {
      d.state.depth_bias.enable = true;
      d.state.depth_bias.constant_factor = float(g.r.pick({0.0, 1.0, -0.5, -1.0, 3.0, tiny()}));
      d.state.depth_bias.slope_factor = float(g.r.pick({0.0, 0.001, 1.0, -2.0, tiny()}));
      d.state.depth_bias.clamp = float(g.r.pick({0.0, 0.0, 1e-30, -1e-30, tiny()}));
    }
    if (g.r.chance(0.2)) d.state.depth_clamp = true;
    g.cull_state(d.state);
  }
}

// Many draws: strips, fans, indexed lists and lines with random state, overlapping.
void gen_many(Gen& g) {
  g.frame({16, 24, 32});
  g.depth_setup();
  const int draws = int(g.r.range(8, 60));
  for (int k = 0; k < draws; ++k) {
    const Topology t = g.r.pick({Topology::TriangleList, Topology::TriangleStrip, Topology::TriangleFan,
                                 Topology::LineList, Topology::LineStrip});
    const uint32_t n = uint32_t(g.r.range(1, 5));
    uint32_t verts = 0;
    switch (t) {
      case Topology::TriangleList: verts = 3 * n; break;
      case Topology::TriangleStrip:
      case Topology::TriangleFan: verts = n + 2; break;
      case Topology::LineList: verts = 2 * n; break;
      case Topology::LineStrip: verts = n + 1; break;
      case Topology::PointList: verts = n; break;
    }
    const bool indexed = g.r.chance(0.3);
    const uint32_t positions = indexed ? std::max<uint32_t>(1, verts / 2 + 1) : verts;
    std::vector<glm::vec4> p;
    for (uint32_t i = 0; i < positions; ++i)
      p.push_back(g.px(g.coord(-4, g.s.width + 4), g.coord(-4, g.s.height + 4), g.depth()));
    std::vector<uint32_t> idx;
    if (indexed)
      for (uint32_t i = 0; i < verts; ++i) idx.push_back(uint32_t(g.r.range(0, positions - 1)));
    Draw& d = g.add(t, p, idx);
    g.cull_state(d.state);
    g.depth_state(d.state);
    if (is_line_topology(t)) g.line_state(d.state);
    if (g.r.chance(0.1)) g.bias_state(d.state);
  }
}

using Generator = void (*)(Gen&);
const std::vector<std::pair<std::string, Generator>>& generators() {
  static const std::vector<std::pair<std::string, Generator>> list{{"tie", gen_tie},
                                                                   {"fan", gen_fan},
                                                                   {"perspective", gen_perspective},
                                                                   {"clip", gen_clip},
                                                                   {"depth", gen_depth},
                                                                   {"viewport", gen_viewport},
                                                                   {"sliver", gen_sliver},
                                                                   {"magnitude", gen_magnitude},
                                                                   {"lines", gen_lines},
                                                                   {"msaa", gen_msaa},
                                                                   {"many", gen_many},
                                                                   {"denormal", gen_denormal}};
  return list;
}

}  // namespace

const std::vector<std::string>& family_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, gen] : generators()) n.push_back(name);
    return n;
  }();
  return names;
}

bool is_family(const std::string& name) {
  const auto& n = family_names();
  return std::find(n.begin(), n.end(), name) != n.end();
}

Scene generate_scene(const std::string& family, uint64_t seed, uint64_t index) {
  const auto& list = generators();
  const auto it = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == family; });
  if (it == list.end()) throw UsageError("unknown soak family \"" + family + "\"");
  uint64_t family_hash = 0xCBF29CE484222325ull;  // FNV-1a: std::hash is implementation-defined
  for (const char c : family) family_hash = (family_hash ^ uint8_t(c)) * 0x100000001B3ull;
  Rng rng(mix64(seed ^ mix64(index + 0x5EEDull)) ^ family_hash);
  Scene scene;
  scene.name = fmt::format("soak.{}.s{}.n{}", family, seed, index);
  scene.description = fmt::format("rastercmp soak --seed {} --family {}: scene {}", seed, family, index);
  Gen g{rng, scene};
  it->second(g);
  // Through the writer and the loader: what runs is what a written file reproduces.
  const std::string text = scene_to_json_text(scene);
  try {
    return parse_scene(text, scene.name + ".json");
  } catch (const InputError& e) {
    throw std::logic_error(fmt::format("soak generator produced an invalid scene: {}\n{}", e.what(), text));
  }
}

}  // namespace rastercmp::soak
