#include "cpu_raster/spec/spec_primitives.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/clip_line.hpp"
#include "cpu_raster/exact/clip_triangle.hpp"
#include "cpu_raster/exact/clip_vertex.hpp"

namespace rastercmp::cpu::spec {
namespace {

struct DrawContext {
  const Scene* scene = nullptr;
  const Draw* draw = nullptr;
  uint32_t draw_index = 0;
  ViewportTransform viewport;
  bool fma = true;
  uint32_t bits = 8;
  double box_half_px = 0;  // half-size of the judged pixel box
  double snap_px = 0;      // how far a device may move a vertex: snapping and float slack
};

bool usable(const WindowVertex& v) {
  const auto ok = [](float c) { return std::isfinite(c) && std::fabs(c) <= kMaxWindowMagnitude; };
  return ok(v.x) && ok(v.y) && std::isfinite(v.z);
}

bool finite(const glm::vec4& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w);
}

// What the state alone decides: FRONT_AND_BACK culls every triangle, depth compare NEVER writes
// nothing (Vulkan "Depth Comparison"); lines are never culled.
Gate state_gate(const Scene& scene, const Draw& draw) {
  if (is_triangle_topology(draw.topology) && draw.state.cull_mode == CullMode::FrontAndBack) return Gate::Never;
  if (scene.has_depth() && draw.state.depth.test_enable && draw.state.depth.compare_op == CompareOp::Never)
    return Gate::Never;
  return Gate::Certain;
}

DepthPrimitive depth_primitive(const DrawContext& ctx, std::initializer_list<WindowVertex> vertices) {
  DepthPrimitive p;
  for (const WindowVertex& v : vertices) p.vertices.emplace_back(v.x, v.y, v.z);
  p.line_width = ctx.draw->state.line_width;
  p.box_half_px = ctx.box_half_px;
  p.snap_px = ctx.snap_px;
  return p;
}

Quad viewport_quad(const Viewport& v) {
  const double x0 = v.x, x1 = double(v.x) + v.width;
  const double y0 = std::min(double(v.y), double(v.y) + v.height), y1 = std::max(double(v.y), double(v.y) + v.height);
  return {{glm::dvec2(x0, y0), glm::dvec2(x1, y0), glm::dvec2(x1, y1), glm::dvec2(x0, y1)}};
}

void add_triangle(const DrawContext& ctx, const cpu::AssembledPrimitive& prim, SpecPrimitives& out) {
  const Draw& draw = *ctx.draw;
  const bool depth_clip = draw.state.depth_clip_enabled();
  std::array<ClipVertex, 3> triangle;
  std::array<glm::vec4, 3> source;
  for (size_t k = 0; k < 3; ++k) {
    source[k] = draw.positions_clip[prim.position[k]];
    if (!finite(source[k])) {
      out.undefined = true;
      return;
    }
    triangle[k] = make_clip_vertex(source[k], ctx.viewport, depth_clip, ctx.fma);
  }
  const ClippedTriangles clipped = clip_triangle(triangle, ctx.viewport);
  if (clipped.fate == ClipFate::Discarded) out.undefined = true;
  for (const std::array<ClipVertex, 3>& piece : clipped.triangles) {
    SpecTriangle t;
    t.draw_index = ctx.draw_index;
    t.primitive_index = prim.primitive_index;
    t.source_clip = source;
    for (size_t k = 0; k < 3; ++k) t.window[k] = piece[k].window;
    if (!std::all_of(t.window.begin(), t.window.end(), usable)) {
      out.undefined = true;
      continue;
    }
    t.snapped = snap_triangle({glm::dvec2(t.window[0].x, t.window[0].y), glm::dvec2(t.window[1].x, t.window[1].y),
                               glm::dvec2(t.window[2].x, t.window[2].y)},
                              ctx.bits);
    t.facing = facing_gate(draw.state, t.snapped.area_sign);
    t.depth = make_depth_judge(*ctx.scene, draw.state, depth_primitive(ctx, {t.window[0], t.window[1], t.window[2]}));
    if (t.facing != Gate::Never) out.triangles.push_back(std::move(t));
  }
}

void add_line(const DrawContext& ctx, const cpu::AssembledPrimitive& prim, SpecPrimitives& out) {
  const Draw& draw = *ctx.draw;
  const bool depth_clip = draw.state.depth_clip_enabled();
  std::array<ClipVertex, 2> line;
  for (size_t k = 0; k < 2; ++k) {
    const glm::vec4& source = draw.positions_clip[prim.position[k]];
    if (!finite(source)) {
      out.undefined = true;
      return;
    }
    line[k] = make_clip_vertex(source, ctx.viewport, depth_clip, ctx.fma);
  }
  const ClippedLine clipped = clip_line(line, ctx.viewport);
  if (clipped.fate == ClipFate::Discarded) out.undefined = true;
  if (clipped.fate == ClipFate::Outside || clipped.fate == ClipFate::Discarded) return;
  const WindowVertex &a = clipped.line[0].window, &b = clipped.line[1].window;
  if (!usable(a) || !usable(b)) {
    out.undefined = true;
    return;
  }
  SpecLine l;
  l.draw_index = ctx.draw_index;
  l.primitive_index = prim.primitive_index;
  l.shape = line_shape({glm::dvec2(a.x, a.y), glm::dvec2(b.x, b.y)}, draw.state.line_mode, draw.state.line_width);
  // Only the segment is clipped: whether a wide line's fragments beyond the viewport rectangle are
  // produced is the device's choice (lavapipe scissors them, docs/lavapipe-rules.md §2.5), so Must stays
  // inside it.
  if (!l.shape.must.empty()) l.shape.must.push_back(viewport_quad(ctx.scene->effective_viewport()));
  l.depth = make_depth_judge(*ctx.scene, draw.state, depth_primitive(ctx, {a, b}));
  out.lines.push_back(std::move(l));
}

}  // namespace

Gate facing_gate(const RasterState& state, int area_sign) {
  if (state.cull_mode == CullMode::None) return Gate::Certain;
  if (state.cull_mode == CullMode::FrontAndBack) return Gate::Never;
  if (area_sign == 0) return Gate::Maybe;
  const bool front = (area_sign > 0) == (state.front_face == FrontFace::CounterClockwise);
  const bool culled = state.cull_mode == CullMode::Front ? front : !front;
  return culled ? Gate::Never : Gate::Certain;
}

Gate triangle_gate_at(const SpecTriangle& triangle, int32_t px, int32_t py) {
  return weaker(triangle.facing, depth_gate_at(triangle.depth, glm::dvec2(px + 0.5, py + 0.5)));
}

SpecPrimitives build_spec_primitives(const Scene& scene, bool fma, uint32_t sub_pixel_bits) {
  SpecPrimitives out;
  DrawContext ctx;
  ctx.scene = &scene;
  ctx.viewport = make_viewport_transform(scene.effective_viewport());
  ctx.fma = fma;
  ctx.bits = sub_pixel_bits;
  const ToleranceBox box = pixel_box(0, 0, sub_pixel_bits, scene.samples > 1);
  ctx.box_half_px = std::ldexp(double(box.half), -int(sub_pixel_bits));
  ctx.snap_px = std::ldexp(2.0, -int(sub_pixel_bits));  // floor/ceil: 1 unit, float slack: 1 unit
  for (uint32_t d = 0; d < scene.draws.size(); ++d) {
    const Draw& draw = scene.draws[d];
    if (state_gate(scene, draw) == Gate::Never) continue;
    ctx.draw = &draw;
    ctx.draw_index = d;
    const uint32_t count = primitive_count(draw);
    for (uint32_t i = 0; i < count; ++i) {
      const cpu::AssembledPrimitive prim = assemble_primitive(draw, i);
      if (is_line_topology(draw.topology))
        add_line(ctx, prim, out);
      else
        add_triangle(ctx, prim, out);
    }
  }
  return out;
}

}  // namespace rastercmp::cpu::spec
