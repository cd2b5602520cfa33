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

// Depth intervals: what the spec's floating-point accuracy allows at the vertices the clipper made.
// "P = t P_1 + (1-t) P_2" with t from the plane distances: about four operations, each accurate to
// kSpecRelativeAccuracy, so a clip coordinate is off by up to 4 eps max|P|, and the divide by w_c
// scales that by 1/|w_c| (and the viewport by p_z, or p_x/2 and p_y/2).
struct ClipError {
  double z = 0, px = 0;
};

ClipError clip_error(const DrawContext& ctx, std::initializer_list<const ClipVertex*> piece,
                     std::initializer_list<glm::vec4> source) {
  ClipError e;
  double magnitude = 0;
  for (const glm::vec4& s : source)
    magnitude = std::max(
        {magnitude, double(std::fabs(s.x)), double(std::fabs(s.y)), double(std::fabs(s.z)), double(std::fabs(s.w))});
  const Viewport v = ctx.scene->effective_viewport();
  const double p_z = std::fabs(double(v.max_depth) - double(v.min_depth));
  const double p_xy = 0.5 * std::max(std::fabs(double(v.width)), std::fabs(double(v.height)));
  for (const ClipVertex* c : piece) {
    if (!c->made_by_clipper) continue;
    const double w = std::fabs(double(c->pos_clip.w));
    const double clip = 4 * kSpecRelativeAccuracy * magnitude / w;
    e.z = std::max(e.z, p_z * clip);
    e.px = std::max(e.px, p_xy * clip);
  }
  return e;
}

double max_abs_window_z(std::initializer_list<const ClipVertex*> vertices) {
  double z = 0;
  for (const ClipVertex* v : vertices)
    if (std::isfinite(v->window.z)) z = std::max(z, double(std::fabs(v->window.z)));
  return z;
}

DepthPrimitive depth_primitive(const DrawContext& ctx, std::initializer_list<WindowVertex> vertices,
                               const ClipError& clip, double source_max_abs_z) {
  DepthPrimitive p;
  for (const WindowVertex& v : vertices) p.vertices.emplace_back(v.x, v.y, v.z);
  p.line_width = ctx.draw->state.line_width;
  p.box_half_px = ctx.box_half_px;
  p.snap_px = ctx.snap_px;
  p.clip_error_z = clip.z;
  p.clip_error_px = clip.px;
  p.source_max_abs_z = source_max_abs_z;
  p.sample_half_px = ctx.scene->samples > 1 ? ctx.box_half_px : 0.0;
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
    t.shape_certain = std::none_of(piece.begin(), piece.end(),
                                   [](const ClipVertex& v) { return v.made_by_clipper && !(v.pos_clip.w > 0.0f); });
    const ClipError error = clip_error(ctx, {&piece[0], &piece[1], &piece[2]}, {source[0], source[1], source[2]});
    t.depth = make_depth_judge(*ctx.scene, draw.state,
                               depth_primitive(ctx, {t.window[0], t.window[1], t.window[2]}, error,
                                               max_abs_window_z({&triangle[0], &triangle[1], &triangle[2]})));
    if (t.facing != Gate::Never) out.triangles.push_back(std::move(t));
  }
}

void add_line(const DrawContext& ctx, const cpu::AssembledPrimitive& prim, SpecPrimitives& out) {
  const Draw& draw = *ctx.draw;
  const bool depth_clip = draw.state.depth_clip_enabled();
  std::array<ClipVertex, 2> line;
  std::array<glm::vec4, 2> source;
  for (size_t k = 0; k < 2; ++k) {
    source[k] = draw.positions_clip[prim.position[k]];
    if (!finite(source[k])) {
      out.undefined = true;
      return;
    }
    line[k] = make_clip_vertex(source[k], ctx.viewport, depth_clip, ctx.fma);
  }
  const ClippedLine clipped = clip_line(line, ctx.viewport);
  if (clipped.fate == ClipFate::Discarded) out.undefined = true;
  if (clipped.fate == ClipFate::Discarded) return;
  // "If either of a line segment's vertices lie outside of the clip volume, the line segment may be
  // clipped": a device may also leave it whole in x and y (a guard band; lavapipe from Mesa 23.2,
  // docs/lavapipe-rules.md §8.2), clipping only against the depth planes. Whatever that line covers
  // is May. Only with both w > 0: past the eye the projected "segment" is not the line's.
  const bool in_front = source[0].w > 0.0f && source[1].w > 0.0f;
  const ClippedLine whole_xy = in_front ? clip_line(line, ctx.viewport, 0, cpu::LineXyClip::GuardBand) : clipped;
  const bool whole_differs =
      whole_xy.fate != ClipFate::Outside && whole_xy.fate != ClipFate::Discarded &&
      (clipped.fate == ClipFate::Outside || clipped.line[0].window.x != whole_xy.line[0].window.x ||
       clipped.line[0].window.y != whole_xy.line[0].window.y || clipped.line[1].window.x != whole_xy.line[1].window.x ||
       clipped.line[1].window.y != whole_xy.line[1].window.y);
  if (clipped.fate == ClipFate::Outside && !whole_differs) return;
  // The segment judged: the clipped one, or the whole one where clipping removes it all.
  const ClippedLine& judged = clipped.fate == ClipFate::Outside ? whole_xy : clipped;
  const WindowVertex &a = judged.line[0].window, &b = judged.line[1].window;
  if (!usable(a) || !usable(b)) {
    out.undefined = true;
    return;
  }
  SpecLine l;
  l.draw_index = ctx.draw_index;
  l.primitive_index = prim.primitive_index;
  l.shape = line_shape({glm::dvec2(a.x, a.y), glm::dvec2(b.x, b.y)}, draw.state.line_mode, draw.state.line_width);
  if (clipped.fate == ClipFate::Outside) l.shape.must.clear();  // clipping may remove it: never Must
  // Only the segment is clipped: whether a wide line's fragments beyond the viewport rectangle are
  // produced is the device's choice (lavapipe scissors them, docs/lavapipe-rules.md §2.5), so Must stays
  // inside it.
  if (!l.shape.must.empty()) l.shape.must.push_back(viewport_quad(ctx.scene->effective_viewport()));
  const ClippedLine* depth_from = &judged;
  if (whole_differs && clipped.fate != ClipFate::Outside) {
    const WindowVertex &wa = whole_xy.line[0].window, &wb = whole_xy.line[1].window;
    if (!usable(wa) || !usable(wb)) {
      out.undefined = true;
      return;
    }
    const LineShape whole =
        line_shape({glm::dvec2(wa.x, wa.y), glm::dvec2(wb.x, wb.y)}, draw.state.line_mode, draw.state.line_width);
    l.shape.may.insert(l.shape.may.end(), whole.may.begin(), whole.may.end());
    depth_from = &whole_xy;  // the same line, so its depth interval holds the clipped one's
  }
  const WindowVertex &da = depth_from->line[0].window, &db = depth_from->line[1].window;
  const ClipError error = clip_error(ctx, {&depth_from->line[0], &depth_from->line[1]}, {source[0], source[1]});
  l.depth = make_depth_judge(*ctx.scene, draw.state,
                             depth_primitive(ctx, {da, db}, error, max_abs_window_z({&line[0], &line[1]})));
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

ViewportRect viewport_rect(const Viewport& v) {
  const double y_end = double(v.y) + double(v.height);
  return {double(v.x), double(v.x) + double(v.width), std::min(double(v.y), y_end), std::max(double(v.y), y_end)};
}

bool box_inside_viewport(const ViewportRect& r, const ToleranceBox& box, uint32_t bits) {
  const double unit = std::ldexp(1.0, -int(bits));
  const double x0 = double(box.cx - box.half) * unit, x1 = double(box.cx + box.half) * unit;
  const double y0 = double(box.cy - box.half) * unit, y1 = double(box.cy + box.half) * unit;
  return x0 > r.x0 && x1 < r.x1 && y0 > r.y0 && y1 < r.y1;
}

Coverage capped(Coverage coverage, const SpecTriangle& t, const ViewportRect& viewport, const ToleranceBox& box,
                uint32_t bits) {
  if (coverage != Coverage::Full) return coverage;
  return t.shape_certain && box_inside_viewport(viewport, box, bits) ? Coverage::Full : Coverage::Partial;
}

Coverage triangle_coverage_at(const SpecTriangle& t, const ViewportRect& viewport, int32_t px, int32_t py,
                              uint32_t bits, bool multisample) {
  const ToleranceBox box = pixel_box(px, py, bits, multisample);
  return capped(classify_box(t.snapped, box), t, viewport, box, bits);
}

Coverage line_coverage_at(const SpecLine& line, int32_t px, int32_t py, uint32_t bits, bool multisample) {
  const double half_px = pixel_box_half_px(bits, multisample);
  return classify_line_box(line.shape, PixelSquare{glm::dvec2(px + 0.5, py + 0.5), half_px});
}

SpecPrimitives build_spec_primitives(const Scene& scene, bool fma, uint32_t sub_pixel_bits) {
  SpecPrimitives out;
  DrawContext ctx;
  ctx.scene = &scene;
  ctx.viewport = make_viewport_transform(scene.effective_viewport());
  ctx.fma = fma;
  ctx.bits = sub_pixel_bits;
  ctx.box_half_px = pixel_box_half_px(sub_pixel_bits, scene.samples > 1);
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
