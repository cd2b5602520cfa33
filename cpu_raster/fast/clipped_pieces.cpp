#include "cpu_raster/fast/clipped_pieces.hpp"

#include <algorithm>
#include <climits>
#include <optional>
#include <utility>

#include "cpu_raster/exact/binned_triangle.hpp"
#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/fast/block_rows.hpp"
#include "cpu_raster/fast/small_block_input.hpp"

namespace rastercmp::cpu::fast {

FastTriangle fast_triangle_of(const RasterPrimitive& p, const PixelRect& region) {
  FastTriangle t;
  for (int k = 0; k < 3; ++k) {
    t.x_fixed[k] = p.vertex_fixed[k].x.raw;
    t.y_fixed[k] = p.vertex_fixed[k].y.raw;
  }
  t.rect = intersect(p.bbox, region);  // coverage lies in the bounding box (§2.5)
  if (p.has_depth) {
    t.a0 = p.depth.a0;
    t.dzdx = p.depth.dzdx;
    t.dzdy = p.depth.dzdy;
    t.offset = p.offset.offset;
  }
  t.owner = p.owner;
  return t;
}

PieceSetup setup_piece(const std::array<WindowVertex, 3>& window_in, uint32_t owner, const SetupContext& ctx,
                       const PixelRect& region, FastTriangle& out) {
  const float pixel_offset = ctx.multisample ? 0.0f : 0.5f;  // calc_fixed_position
  const std::optional<std::array<FixedPoint, 3>> snapped = snap_triangle(window_in, pixel_offset, ctx.methods.snap);
  if (!snapped || !in_direct_range(*snapped)) return PieceSetup::Full;
  std::array<FixedPoint, 3> fixed = *snapped;
  const int64_t area = doubled_area(fixed);
  if (area == 0) return PieceSetup::Dropped;  // always dropped
  const RasterState& state = *ctx.state;
  if (face_culled((area > 0) == (state.front_face == FrontFace::CounterClockwise), state.cull_mode))
    return PieceSetup::Dropped;
  std::array<WindowVertex, 3> window = window_in;
  if (area < 0) {  // rotate_fixed_position_12 with flatshade_first: (v0, v2, v1)
    std::swap(fixed[1], fixed[2]);
    std::swap(window[1], window[2]);
  }
  // place_in_region drops a piece whose box misses the region (its cut of x0, y0 at 0 changes
  // nothing inside the region)
  const PixelRect bbox = triangle_bbox(fixed);
  if (!rects_touch(ctx.region, bbox)) return PieceSetup::Dropped;
  out = FastTriangle{};
  for (int k = 0; k < 3; ++k) {
    out.x_fixed[k] = fixed[k].x.raw;
    out.y_fixed[k] = fixed[k].y.raw;
  }
  out.rect = intersect(bbox, region);
  if (ctx.depth_active()) {  // setup_triangle forms them when wanted; fast_triangle_of keeps them when active
    const DepthPlane plane = triangle_depth_plane(window, pixel_offset);
    out.a0 = plane.a0;
    out.dzdx = plane.dzdx;
    out.dzdy = plane.dzdy;
    out.offset =
        triangle_depth_offset(window, state.depth_bias, ctx.depth_format, ctx.skips.bias_only_when_enabled,
                              unorm_bias_units(ctx.rules))
            .offset;
  }
  out.owner = owner;
  return PieceSetup::Drawn;
}

namespace {

// The tile rows the lanes of a kBlockAnyRow block reach, gathered lane by lane: a lane whose
// corners all have known rows by those rows (as block_tile_rows), a clipped one by its pieces'
// rectangles. The other lanes draw nothing (BandWorker::triangle): all three corners outside one
// plane (ClipFate::Outside), or a corner that failed to snap (SetupFate::NonFinite). A clipped
// lane whose pieces take llvmpipe's wrapping set-up (drawn where each worker meets them) keeps the
// block at kBlockAnyRow.
struct LaneRows {
  int32_t lo = INT32_MAX, hi = INT32_MIN;
  bool any_row = false;

  void add(int32_t row_lo, int32_t row_hi) {
    lo = std::min(lo, row_lo);
    hi = std::max(hi, row_hi);
  }
  uint32_t packed(const PixelRect& region) const { return any_row ? kBlockAnyRow : pack_rows(lo, hi, region); }
};

template <Topology T, bool Indexed>
bool clip_blocks(FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end, ClippedTable& table,
                 uint32_t watch_from) {
  const Draw& draw = frame.scene->draws[d];
  FastDraw& fd = frame.draws[d];
  const uint32_t count = primitive_count(draw);
  // The clipped lanes of the trailing run are watched together: the flags cleared before the
  // first of them, read after the last (between them only integer work runs), instead of a
  // DenormalWatch around each.
  bool watching = false;
  SmallBlock block;
  for (uint32_t b = begin; b < end; ++b) {
    if (fd.block_rows[b] != kBlockAnyRow) continue;  // known rows: no corner needs clipping
    fill_block_corners<T, Indexed>(draw.indices.data(), count, b, block);
    const SmallBlockInput& in = block.in;
    LaneRows rows;
    for (uint32_t l = 0; l < in.count; ++l) {
      const size_t at = size_t(l) * in.stride;
      const uint32_t a = in.corners[0][at], bb = in.corners[1][at], c = in.corners[2][at];
      const int32_t ra = fd.tile_rows[a], rb = fd.tile_rows[bb], rc = fd.tile_rows[c];
      if (!is_unknown_row(ra) && !is_unknown_row(rb) && !is_unknown_row(rc)) {
        rows.add(std::min({ra, rb, rc}), std::max({ra, rb, rc}));
        continue;
      }
      // the clip bits from the compact rows (fast_vertices.hpp): 2 bytes a corner
      if (!needs_clipping(row_clip_bits(ra), row_clip_bits(rb), row_clip_bits(rc))) continue;
      ClippedPrimitive entry;
      entry.primitive = block.first + l;
      entry.first = uint32_t(table.pieces.size());
      if (!watching && entry.primitive >= watch_from) {
        clear_denormal_flags();
        watching = true;
      }
      for_each_piece(
          frame, d, entry.primitive, a, bb, c,
          [&](const FastTriangle& t) {
            table.pieces.push_back(t);
            if (!t.rect.empty()) rows.add(t.rect.y0 >> kTileOrder, t.rect.y1 >> kTileOrder);
          },
          [&](const RasterPrimitive&) { entry.in_place = true; });
      rows.any_row |= entry.in_place;
      entry.count = uint32_t(table.pieces.size()) - entry.first;
      table.primitives.push_back(entry);
    }
    fd.block_rows[b] = rows.packed(frame.exact.region);
  }
  return watching && denormal_flags_raised();
}

}  // namespace

bool clip_block_triangles(FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end, ClippedTable& table,
                          uint32_t watch_from) {
  return on_triangle_layout(
      frame.scene->draws[d],
      [&](auto topology, auto indexed) {
        return clip_blocks<topology(), indexed()>(frame, d, begin, end, table, watch_from);
      },
      [] { return false; });
}

void index_clipped(std::vector<ClippedEntry>& entries, const ClippedTable& table) {
  for (const ClippedPrimitive& p : table.primitives)
    entries.push_back({p.primitive, p.count, table.pieces.data() + p.first, p.in_place});
}

}  // namespace rastercmp::cpu::fast
