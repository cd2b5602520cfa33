// BandWorker's exact draws (lines, 4x frames, whatever the fast walk does not take): the exact
// front end over the draw, each primitive left out before its clipping and set-up where it cannot
// reach this worker's rows, and the exact rasterizer's rows cut to the worker's tiles.
#include <algorithm>
#include <array>
#include <cmath>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/clip_line.hpp"
#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/exact/clip_vertex.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/fast/band_worker.hpp"
#include "cpu_raster/fast/exact_reach.hpp"
#include "cpu_raster/fast/exact_rows.hpp"
#include "cpu_raster/fast/lean_setup.hpp"
#include "cpu_raster/fast/trailing_check.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu::fast {
namespace {

// set_up() watched for the MXCSR's denormal flags (DE, UE): read before (cleared when raised) and
// after, written only when raised; `raised` says whether set_up raised one. Its result.
template <class SetUp>
auto watch_denormal_flags(SetUp&& set_up, bool& raised) {
  if (denormal_flags_raised()) clear_denormal_flags();
  auto result = set_up();
  raised = denormal_flags_raised();
  if (raised) clear_denormal_flags();
  return result;
}

}  // namespace

// Draws the fast path does not handle: the exact front end, each primitive's visit rectangle cut
// to this worker's tile rows, and the exact rasterizer's evaluation on the same targets (each row's
// columns cut to the primitive's, exact_rows.hpp). A primitive that cannot reach this worker's
// rows is left out before its clipping and set-up (misses_own_rows).
bool BandWorker::walk_exact(uint32_t d) {
  const FrameContext& frame = frame_.exact;
  const DepthTestState& depth = frame_.draws[d].raster.depth;
  // the vertex phase's window positions and clip bits (fast_vertices.hpp: make_clip_vertex's
  // operations), where it ran for this draw; its clip bits also give the chunk flags
  const FastVertex* transformed = frame_.draws[d].vertices;
  const size_t positions = frame_.scene->draws[d].positions_clip.size();
  const DrawWalk walk = transformed ? begin_draw_transformed(d) : begin_draw(frame, d);
  const OutcomeSink sink = [&](const PrimitiveOutcome& outcome) {
    if (outcome.rasterized()) raster_exact_in_band(outcome.raster, depth);
  };
  const bool lines = walk.base.is_line, depth_clip = walk.draw->state.depth_clip_enabled();
  const float margin = reach_margin(*walk.draw, lines);  // how far a visit reaches past its vertices
  const uint32_t corners = lines ? 2 : 3;
  // Lines: run_line's calls (clip, set-up in the primitive's mode) without the outcome's
  // bookkeeping. A triangle run_triangle would pass unclipped to set-up, without the pipeline's
  // float cull, in the flushed mode: the lean set-up (lean_setup.hpp) from its corners. The
  // clipper returns a triangle with every vertex inside unchanged unless the clip skip is off
  // (clip_triangle); anything else takes run_primitive.
  const bool lean_triangles = !lines && frame.skips.clip_only_when_needed;
  const bool float_cull = walk.draw->state.cull_mode != CullMode::None;
  // clip_line's arguments, as the reach phase's (clipped_line_reach); inside_planes also the
  // triangles' test below
  const LineClipping clipping = line_clipping(frame, *walk.draw);
  const uint32_t inside_planes = clipping.inside_planes;
  const bool bias_denormal = lines && depth_bias_is_denormal(walk.draw->state.depth_bias);
  const LineXyClip line_xy = clipping.xy;
  // A line or triangle list: primitive i's corners are positions (indices[]) corners * i + k, so a
  // primitive in other workers' rows is left out from the vertex phase's values before it is
  // assembled: from the tile rows the reach phase stored (exact_reach.hpp), or worked out here.
  const bool listed = transformed && frame_.workers > 1 &&
                      walk.draw->topology == (lines ? Topology::LineList : Topology::TriangleList);
  const uint32_t* list_reach = frame_.draws[d].list_reach;
  // A primitive that throws (set-up in a mode where the two modes disagree, a refused wrapping
  // set-up) stops this walk; the render throws the first such primitive's error (FastFrame::failure).
  uint32_t i = 0;
  try {
    for (; i < walk.count; ++i) {
      if (listed) {
        const RowReach reach = list_reach
                                   ? reach_of_tile_rows(list_reach[i])
                                   : reach_of(listed_row_span(*walk.draw, transformed, positions, corners, i, margin));
        if (reach == RowReach::OtherRows) continue;
        if (reach == RowReach::NoFrameRow && primitive_setup_denormals(walk, i) == SetupDenormals::Flushed) continue;
      }
      const SetupDenormals mode = primitive_setup_denormals(walk, i);
      const bool flushed = mode == SetupDenormals::Flushed;
      if (!lines && frame_.workers == 1 && (!flushed || !lean_triangles)) {
        run_primitive(frame, walk, i, sink);
        continue;
      }
      const AssembledPrimitive prim = assemble_primitive(*walk.draw, i);
      // each corner's make_clip_vertex fields but its pos_clip (the position itself, read only
      // where a line is clipped): from the vertex phase where it ran
      std::array<WindowVertex, 3> corner;
      std::array<uint32_t, 3> clip_bits{};  // a line leaves the third 0
      for (uint32_t k = 0; k < corners; ++k) {
        const uint32_t position = prim.position[k];
        if (transformed && position < positions) {
          const FastVertex& t = transformed[position];
          corner[k] = WindowVertex{t.x, t.y, t.z};
          clip_bits[k] = t.flags & kVertexClipBits;
        } else {
          const ClipVertex v =
              make_clip_vertex(walk.draw->positions_clip[position], frame.viewport, depth_clip, frame.fma);
          corner[k] = v.window;
          clip_bits[k] = v.clip_mask;
        }
      }
      // a listed primitive had this test on these values above
      if (frame_.workers > 1 && !listed && misses_own_rows(corner.data(), clip_bits.data(), corners, margin, !flushed))
        continue;
      const uint32_t owner = encode_owner(d, prim.primitive_index);
      if (lines) {
        std::array<WindowVertex, 2> window{corner[0], corner[1]};
        // Both ends inside every clip plane and no pass forced (inside_planes 0): clip_line hands
        // the line back as it is (clip_line.cpp, §1.5), so it is called only otherwise.
        if ((clip_bits[0] | clip_bits[1]) != 0 || inside_planes != 0) {
          const auto clip_vertex = [&](uint32_t k) {
            return ClipVertex{walk.draw->positions_clip[prim.position[k]], corner[k], clip_bits[k], false};
          };
          const ClippedLine clipped =
              clip_line({clip_vertex(0), clip_vertex(1)}, frame.viewport, inside_planes, line_xy);
          if (clipped.fate == ClipFate::Outside || clipped.fate == ClipFate::Discarded) continue;
          window = {clipped.line[0].window, clipped.line[1].window};
          // a line the clipper cut was not settled by its vertices above: its cut ends are set-up's input
          if (frame_.workers > 1 && clipped.fate == ClipFate::Clipped &&
              clipped_line_misses_own_rows(window, margin, !flushed))
            continue;
        }
        const bool lean_line = frame_.raster.avx2 && (flushed || !bias_denormal);
        const LeanSetup lean =
            lean_line ? setup_line_lean_flushed(flushed, window, owner, walk.ctx) : LeanSetup::Full;
        if (lean == LeanSetup::Drawn) raster_exact_in_band(lean_, depth);
        if (lean != LeanSetup::Full) continue;
        const LineSetup setup =
            setup_line_flushed(mode, window, owner, walk.ctx, prim.primitive_index, bias_denormal);
        if (setup.fate == SetupFate::Rasterized) raster_exact_in_band(setup.raster, depth);
        continue;
      }
      const bool inside = (clip_bits[0] | clip_bits[1] | clip_bits[2]) == 0;
      if (!flushed || !lean_triangles || !inside || (float_cull && walk.pipelined[i / walk.per_chunk])) {
        run_primitive(frame, walk, i, sink);
        continue;
      }
      // the workers run with denormals flushed (WorkerPool::call, render_fast_into)
      const LeanSetup lean = frame_.raster.avx2 ? setup_triangle_lean(corner, owner, walk.ctx, lean_) : LeanSetup::Full;
      if (lean == LeanSetup::Drawn) raster_exact_in_band(lean_, depth);
      if (lean != LeanSetup::Full) continue;
      const TriangleSetup setup =
          setup_triangle_in_mode(SetupDenormals::Flushed, corner, owner, walk.ctx, prim.primitive_index);
      if (setup.fate == SetupFate::Rasterized) raster_exact_in_band(setup.raster, depth);
    }
  } catch (...) {
    frame_.record_failure(d, i, std::current_exception());
    return false;
  }
  return true;
}

// setup_line_in_mode in a worker, which runs with denormals flushed: a line set up in the flushed
// mode is setup_line's result as it is; one in a trailing run (Kept, EitherMustAgree) is too when
// no set-up operation met a denormal and no bias factor is one (setup_in_mode, front_end.cpp), and
// otherwise goes to setup_line_in_mode, which sets it up again in both modes. The MXCSR's flags are
// read before and after, and written only when raised: one write in place of the scoped mode's and
// the watch's three per line.
LineSetup BandWorker::setup_line_flushed(SetupDenormals mode, const std::array<WindowVertex, 2>& window,
                                         uint32_t owner, const SetupContext& ctx, uint32_t primitive_index,
                                         bool bias_denormal) {
  if (mode == SetupDenormals::Flushed) return setup_line(window, owner, ctx);
  if (bias_denormal) return setup_line_in_mode(mode, window, owner, ctx, primitive_index);
  bool raised = false;
  LineSetup setup = watch_denormal_flags([&] { return setup_line(window, owner, ctx); }, raised);
  if (!raised) return setup;
  return setup_line_in_mode(mode, window, owner, ctx, primitive_index);
}

// setup_line_lean where setup_line_flushed would hand back setup_line's result: in the flushed
// mode, and in a trailing run's mode when no operation raised a denormal flag (the lean set-up
// makes setup_line's float operations in its order; its roundings raise none). Full otherwise, so
// that setup_line_flushed sets the line up again (in both modes when a flag was raised).
LeanSetup BandWorker::setup_line_lean_flushed(bool flushed, const std::array<WindowVertex, 2>& window, uint32_t owner,
                                              const SetupContext& ctx) {
  if (flushed) return setup_line_lean(window, owner, ctx, lean_);
  bool raised = false;
  const LeanSetup lean = watch_denormal_flags([&] { return setup_line_lean(window, owner, ctx, lean_); }, raised);
  return raised ? LeanSetup::Full : lean;
}

// begin_draw with the chunk flags and trailing run formed from the vertex phase's clip bits (as
// for the fast draws, render_fast.cpp). A position past the draw's counts as unclipped: such an
// index makes the render throw (the profile check) before any walk.
DrawWalk BandWorker::begin_draw_transformed(uint32_t d) const {
  std::vector<bool> pipelined = transformed_pipelined_chunks(frame_, d);
  const TrailingPipelineRun run = transformed_trailing_run(frame_, d, pipelined);
  return begin_draw(frame_.exact, d, std::move(pipelined), run);
}

// Whether a primitive certainly reaches none of this worker's tile rows: every vertex inside every
// clip plane (the clipper passes it unchanged, so these window positions are set-up's input),
// finite, spanning less than 32000 px in x plus y with the margin (so its edges stay in the direct
// range: no wrapping set-up, lavapipe-rules §7.5), and its window y extent widened by `margin` on
// each side in no row this worker owns. Leaving it out changes nothing in these rows. A primitive
// set up with denormals flushed then cannot throw. One set up in the other mode (`may_throw`)
// throws where the two modes disagree; it is left out only where its rows meet the frame's tile
// rows, every one of which some worker owns (row_balance, contiguous_rows): a worker that owns one
// sets it up, in order, and records its error (walk_exact, FastFrame::failure), which is then
// the first failing primitive's, as on the exact path.
bool BandWorker::misses_own_rows(const WindowVertex* window, const uint32_t* clip_bits, uint32_t count, float margin,
                                 bool may_throw) const {
  const auto vertex = [window, clip_bits](uint32_t k) { return std::pair{window[k], clip_bits[k]}; };
  return span_misses_own_rows(row_span_of(count, margin, vertex), may_throw);
}

// misses_own_rows for a line the clipper cut, from its clipped ends' window positions (which
// set-up takes as they are, whatever their clip bits).
bool BandWorker::clipped_line_misses_own_rows(const std::array<WindowVertex, 2>& window, float margin,
                                              bool may_throw) const {
  const auto vertex = [&window](uint32_t k) { return std::pair{window[k], 0u}; };
  return span_misses_own_rows(row_span_of(2, margin, vertex), may_throw);
}

// The verdict of both: a span in other workers' rows only, or in no frame row when its set-up
// cannot throw.
bool BandWorker::span_misses_own_rows(const RowSpan& span, bool may_throw) const {
  const RowReach reach = reach_of(span);
  return reach == RowReach::OtherRows || (reach == RowReach::NoFrameRow && !may_throw);
}

BandWorker::RowReach BandWorker::reach_of(const RowSpan& span) const {
  return span.settled ? reach_of_tiles(span.lo >> kTileOrder, span.hi >> kTileOrder) : RowReach::Unsettled;
}

// reach_of for the tile rows the reach phase stored: the same answer (their clamp to [-1,
// tiles_y] changes none, exact_reach.hpp).
BandWorker::RowReach BandWorker::reach_of_tile_rows(uint32_t packed) const {
  if (packed == kReachUnsettled) return RowReach::Unsettled;
  const auto [lo, hi] = unpack_tile_rows(packed);
  return reach_of_tiles(lo, hi);
}

// Tile rows [lo, hi] (any integers): some of this worker's, none of them, or none of the frame's.
BandWorker::RowReach BandWorker::reach_of_tiles(int32_t lo, int32_t hi) const {
  if (owns_tile_rows(lo, hi)) return RowReach::OwnRows;
  return hi < 0 || lo >= frame_.raster.tiles_y ? RowReach::NoFrameRow : RowReach::OtherRows;
}

void BandWorker::raster_exact_in_band(const RasterPrimitive& primitive, const DepthTestState& depth) {
  const PixelRect& visit = primitive.visit;
  if (visit.empty()) return;
  // Most often every tile row of the visit is all this worker's: drawn whole, in one call (the visit
  // lies in the framebuffer, so the cut below would leave it as it is, in pieces), every column of
  // its rows the worker's (owned_row_end: the frame's last, short of a wider pitch's extra columns).
  const int32_t ty_lo = visit.y0 >> kTileOrder, ty_hi = visit.y1 >> kTileOrder;
  if (ty_lo >= 0 && whole_before_[size_t(ty_hi) + 1] - whole_before_[size_t(ty_lo)] == uint32_t(ty_hi - ty_lo + 1)) {
    prepare_tiles(visit, depth.write);
    if (frame_.raster.avx512 && rasterize_box_avx512(primitive, visit.y0, visit.y1, depth, frame_.targets)) return;
    if (frame_.raster.avx2 &&
        rasterize_rows_avx2(primitive, visit.y0, visit.y1, depth, frame_.targets, frame_.raster.avx512,
                           int32_t(frame_.scene->width) - 1))
      return;
    if (primitive.binned)
      rasterize_binned_rows(primitive, depth, frame_.targets, frame_.raster.avx2);
    else
      rasterize_primitive_rows(primitive, depth, frame_.targets, frame_.raster.avx2);
    return;
  }
  const int32_t tx_lo = std::max(visit.x0 >> kTileOrder, 0);
  const int32_t tx_hi = std::min(visit.x1 >> kTileOrder, frame_.raster.tiles_x - 1);
  for (int32_t ty = visit.y0 >> kTileOrder; ty <= visit.y1 >> kTileOrder; ++ty) {
    if (!owns_tile_row(ty)) continue;
    const int32_t y0 = std::max(visit.y0, ty * kTileSize), y1 = std::min(visit.y1, ty * kTileSize + kTileSize - 1);
    RasterPrimitive band = primitive;
    band.visit.y0 = y0;
    band.visit.y1 = y1;
    // each run of this worker's tiles in the row (the whole visit where the row is its own); a
    // sample's coverage and depth do not depend on the columns visited beside it
    for (int32_t tx = tx_lo; tx <= tx_hi; ++tx) {
      if (!owns_tile(tx, ty)) continue;
      int32_t last = tx;
      while (last < tx_hi && owns_tile(last + 1, ty)) ++last;
      band.visit.x0 = std::max(visit.x0, tx * kTileSize);
      band.visit.x1 = std::min(visit.x1, last * kTileSize + kTileSize - 1);
      tx = last;
      prepare_tiles(band.visit, depth.write);
      if (frame_.raster.avx512 && rasterize_box_avx512(band, y0, y1, depth, frame_.targets)) continue;
      if (frame_.raster.avx2 && rasterize_rows_avx2(band, y0, y1, depth, frame_.targets, frame_.raster.avx512))
        continue;
      if (band.binned)  // llvmpipe's wrapping set-up: coverage from its bins, not a plane test
        rasterize_binned_rows(band, depth, frame_.targets, frame_.raster.avx2);
      else
        rasterize_primitive_rows(band, depth, frame_.targets, frame_.raster.avx2);
    }
  }
}

// Before the exact rasterizer writes into r: its tiles cleared, their bounds dropped if depth is
// written (stored only when not dropped yet: a tile state's line may hold a tile of another
// worker's row, and a store would take it from that worker's cache at every primitive).
void BandWorker::prepare_tiles(const PixelRect& r, bool depth_write) {
  for (int32_t ty = r.y0 >> kTileOrder; ty <= r.y1 >> kTileOrder; ++ty) {
    for (int32_t tx = r.x0 >> kTileOrder; tx <= r.x1 >> kTileOrder; ++tx) {
      TileState& tile = frame_.raster.tile(tx, ty);
      if (!tile.cleared) clear_tile_row(ty, index_, frame_.raster);
      if (depth_write && tile.bounds.state != BoundsState::Unknown) tile.bounds.state = BoundsState::Unknown;
    }
  }
}

}  // namespace rastercmp::cpu::fast
