#include "cpu_raster/classic/classic_front_end.hpp"

#include <optional>
#include <vector>

#include "cpu_raster/classic/classic_clip.hpp"
#include "cpu_raster/classic/classic_cull.hpp"
#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/clip_line.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"
#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/line_setup.hpp"
#include "cpu_raster/exact/pipeline_cull.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu::classic {
namespace {

// What one draw's primitives share.
struct DrawContext {
  const FrameContext* frame = nullptr;
  const ClassicMethods* methods = nullptr;
  const Draw* draw = nullptr;
  SetupContext setup;
  DepthTestState depth;
  std::vector<CulledTriangle>* culled = nullptr;  // explain: the triangles normal_dot_view removes
  std::vector<bool> pipelined;  // per draw chunk: some vertex needs clipping (§1.5): the float cull runs (§2.6)
  uint32_t per_chunk = 1;
  TrailingPipelineRun trailing;  // set-up outside the denormal mode (front_end.hpp, §7.11)

  bool chunk_pipelined(uint32_t primitive) const { return pipelined[primitive / per_chunk]; }
  SetupDenormals setup_mode(uint32_t primitive) const {
    return setup_denormals(trailing, chunk_pipelined(primitive), primitive);
  }
};

template <size_t N>
std::array<ClipVertex, N> clip_vertices(const DrawContext& dc, const AssembledPrimitive& prim) {
  std::array<ClipVertex, N> vertices;
  for (size_t k = 0; k < N; ++k)
    vertices[k] = make_clip_vertex(dc.draw->positions_clip[prim.position[k]], dc.frame->viewport,
                                   dc.draw->state.depth_clip_enabled(), dc.frame->fma);
  return vertices;
}

// Whether a clipper made one of the vertices (the exact clipper does not mark the ones it makes).
template <size_t N>
bool any_made(const std::array<ClipVertex, N>& vertices, const std::array<ClipVertex, N>& originals) {
  for (const ClipVertex& v : vertices) {
    if (v.made_by_clipper) return true;
    bool original = false;
    for (const ClipVertex& o : originals) original = original || v.pos_clip == o.pos_clip;
    if (!original) return true;
  }
  return false;
}

ClassicPrimitive make_primitive(const DrawContext& dc, uint32_t primitive_index, bool is_line) {
  ClassicPrimitive primitive;
  primitive.draw_index = dc.setup.draw_index;
  primitive.primitive_index = primitive_index;
  primitive.is_line = is_line;
  primitive.depth = dc.depth;
  return primitive;
}

void run_triangle(const DrawContext& dc, const AssembledPrimitive& prim, std::vector<ClassicPrimitive>& out) {
  const std::array<ClipVertex, 3> triangle = clip_vertices<3>(dc, prim);
  const RasterState& state = dc.draw->state;
  const bool nv_cull = dc.methods->cull == CullMethod::NormalDotView;
  if (nv_cull) {
    const std::array<glm::vec4, 3> pos_clip{triangle[0].pos_clip, triangle[1].pos_clip, triangle[2].pos_clip};
    const NormalDotView test = normal_dot_view(pos_clip, state.cull_mode, state.front_face);
    if (test.culled) {
      if (dc.culled)
        dc.culled->push_back({dc.setup.draw_index,
                              prim.primitive_index,
                              pos_clip,
                              {triangle[0].window, triangle[1].window, triangle[2].window},
                              test});
      return;
    }
  }
  const bool depth_clip = state.depth_clip_enabled();
  const auto exact_pieces = [&] {
    const ClippedTriangles clipped = clip_triangle(triangle, dc.frame->viewport);
    return std::vector<std::array<ClipVertex, 3>>(clipped.triangles.begin(), clipped.triangles.end());
  };
  const std::vector<std::array<ClipVertex, 3>> pieces =
      dc.methods->clip == ClipMethod::SutherlandHodgman
          ? clip_triangle_sutherland_hodgman(triangle, dc.frame->viewport, depth_clip)
      : dc.methods->clip == ClipMethod::WeilerAtherton
          ? clip_triangle_weiler_atherton(triangle, dc.frame->viewport, depth_clip)
          : exact_pieces();
  const uint32_t owner = encode_owner(dc.setup.draw_index, prim.primitive_index);
  for (size_t k = 0; k < pieces.size(); ++k) {
    const std::array<ClipVertex, 3>& piece = pieces[k];
    const std::array<WindowVertex, 3> window{piece[0].window, piece[1].window, piece[2].window};
    if (!nv_cull && dc.chunk_pipelined(prim.primitive_index) && state.cull_mode != CullMode::None &&
        pipeline_cull_drops(pipeline_cull_determinant(window), state.cull_mode, state.front_face))  // §2.6
      continue;
    const TriangleSetup setup =
        setup_triangle_in_mode(dc.setup_mode(prim.primitive_index), window, owner, dc.setup, prim.primitive_index);
    if (setup.fate != SetupFate::Rasterized) continue;
    ClassicPrimitive primitive = make_primitive(dc, prim.primitive_index, false);
    primitive.clipped = any_made(piece, triangle);
    primitive.piece = uint32_t(k);
    primitive.pieces = uint32_t(pieces.size());
    primitive.window = window;
    primitive.w_clip = {piece[0].pos_clip.w, piece[1].pos_clip.w, piece[2].pos_clip.w};
    primitive.raster = setup.raster;
    if (dc.methods->clip == ClipMethod::SutherlandHodgman || dc.methods->clip == ClipMethod::WeilerAtherton) {
      primitive.vertex_codes_traced = true;
      for (size_t v = 0; v < 3; ++v) primitive.vertex_codes[v] = clip_space_outcode(triangle[v], depth_clip);
    }
    out.push_back(primitive);
  }
}

std::optional<LineClipper> line_clipper(ClipMethod clip) {
  switch (clip) {
    case ClipMethod::CohenSutherland: return LineClipper::CohenSutherland;
    case ClipMethod::CohenSutherland3d: return LineClipper::CohenSutherland3d;
    case ClipMethod::LiangBarsky: return LineClipper::LiangBarsky;
    case ClipMethod::CyrusBeck: return LineClipper::CyrusBeck;
    default: return std::nullopt;  // the triangle clippers leave lines to the exact clipper
  }
}

void run_line(const DrawContext& dc, const AssembledPrimitive& prim, std::vector<ClassicPrimitive>& out) {
  const std::array<ClipVertex, 2> line = clip_vertices<2>(dc, prim);
  std::array<ClipVertex, 2> clipped;
  const std::optional<LineClipper> clipper = line_clipper(dc.methods->clip);
  LineClipTrace trace;
  if (clipper) {
    ClassicClippedLine result =
        clip_line_classic(line, dc.frame->viewport, dc.draw->state.depth_clip_enabled(), *clipper);
    if (!result.visible) return;
    clipped = result.line;
    trace = std::move(result.trace);
  } else {
    const LineXyClip xy =
        dc.frame->rules.has(LavapipeRule::LineGuardBand) ? LineXyClip::GuardBand : LineXyClip::Clip;  // §8.2
    const ClippedLine result = clip_line(line, dc.frame->viewport, 0, xy);
    if (result.fate == ClipFate::Outside || result.fate == ClipFate::Discarded) return;
    clipped = result.line;
  }
  const LineSetup setup =
      setup_line_in_mode(dc.setup_mode(prim.primitive_index), {clipped[0].window, clipped[1].window},
                         encode_owner(dc.setup.draw_index, prim.primitive_index), dc.setup, prim.primitive_index);
  if (setup.fate != SetupFate::Rasterized) return;
  ClassicPrimitive primitive = make_primitive(dc, prim.primitive_index, true);
  primitive.clipped = any_made(clipped, line);
  primitive.window = {clipped[0].window, clipped[1].window, WindowVertex{}};
  primitive.w_clip = {clipped[0].pos_clip.w, clipped[1].pos_clip.w, 1};
  primitive.raster = setup.raster;
  primitive.line_clip_traced = clipper.has_value();
  primitive.line_clip = std::move(trace);
  out.push_back(std::move(primitive));
}

}  // namespace

void collect_primitives(const FrameContext& frame, uint32_t draw_index, const ClassicMethods& methods,
                        std::vector<ClassicPrimitive>& out, std::vector<CulledTriangle>* culled) {
  const Draw& draw = frame.scene->draws[draw_index];
  // normal_dot_view has culled before clipping; the set-up then culls nothing.
  RasterState state = draw.state;
  if (methods.cull == CullMethod::NormalDotView) state.cull_mode = CullMode::None;
  DrawContext dc;
  dc.frame = &frame;
  dc.methods = &methods;
  dc.draw = &draw;
  dc.setup = make_setup_context(frame, draw_index);
  dc.setup.state = &state;
  dc.depth = make_depth_test_state(*frame.scene, draw, frame.viewport, frame.fma);
  dc.culled = culled;
  dc.pipelined = pipelined_chunks(draw, draw.state.depth_clip_enabled());
  dc.per_chunk = primitives_per_chunk(draw);
  dc.trailing = trailing_pipeline_run(draw, dc.pipelined);
  const bool is_line = is_line_topology(draw.topology);
  const uint32_t count = primitive_count(draw);
  for (uint32_t i = 0; i < count; ++i) {
    const AssembledPrimitive prim = assemble_primitive(draw, i);
    if (is_line)
      run_line(dc, prim, out);
    else
      run_triangle(dc, prim, out);
  }
}

}  // namespace rastercmp::cpu::classic
