// Triangles that need clipping, set up once per frame instead of once per worker. A clipped
// triangle's corners give no tile row (their window positions say nothing before clipping), so
// its block is set up by every worker, and each ran the exact clipper and set-up on it
// (perspective's 614 clipped triangles at the screen's sides and far plane: about 10% of each
// worker's profile, 25d649c). With several workers the block-row phase, which already visits
// those blocks, now clips each once (the task that measures its block) into a ClippedTable per
// draw, and from the pieces' rectangles gives the block the rows it reaches (set up only by their
// workers since 53be80d); the walk then draws the stored pieces in its rows. The pieces are the exact path's
// (clip_triangle, pipeline cull, setup_triangle, or setup_piece, its lean twin for the pieces the kernels draw),
// computed by the same function either way (for_each_piece).
#pragma once

#include <cstdint>
#include <vector>

#include "cpu_raster/exact/clip_triangle.hpp"
#include "cpu_raster/exact/clip_vertex.hpp"
#include "cpu_raster/exact/pipeline_cull.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "cpu_raster/exact/triangle_setup.hpp"
#include "cpu_raster/fast/fast_frame.hpp"
#include "cpu_raster/fast/fast_triangle.hpp"
#include "model/render_result.hpp"

namespace rastercmp::cpu::fast {

// The fast path's triangle for a set-up primitive: its snapped corners (post-swap), its bounding
// box cut to the draw region, depth plane and offset, owner.
FastTriangle fast_triangle_of(const RasterPrimitive& p, const PixelRect& region);

// setup_triangle then fast_triangle_of for a piece, without the parts of the RasterPrimitive the
// fast kernels never read (edge and scissor planes, visit rectangle; perspective's 614 clipped
// triangles took 194 ns of set-up each for their 1.5 pieces, d98ee19): the same snap (§2.2),
// area, cull and swap (§2.3), bounding box and region test (§2.5), depth plane and offset (§3.2,
// §4.3), in the same operations. Full: the piece needs what only setup_triangle does (a corner
// that fails to snap, or an edge past llvmpipe's direct range: its wrapping set-up, §7.5), so
// call that. Dropped: setup_triangle would not rasterize it.
enum class PieceSetup { Drawn, Dropped, Full };
PieceSetup setup_piece(const std::array<WindowVertex, 3>& window, uint32_t owner, const SetupContext& context,
                       const PixelRect& region, FastTriangle& out);

// The exact path's clipper and set-up (front_end.cpp run_triangle) for triangle `primitive` of
// draw d (positions a, b, c), which needs clipping: piece(t) for each piece the fast kernels draw
// (t.rect cut to the draw region, maybe empty), binned(p) for each that takes llvmpipe's wrapping
// set-up, in the clipper's order.
template <class Piece, class Binned>
void for_each_piece(const FastFrame& frame, uint32_t d, uint32_t primitive, uint32_t a, uint32_t b, uint32_t c,
                    Piece&& piece, Binned&& binned) {
  const Draw& draw = frame.scene->draws[d];
  const FastDraw& fd = frame.draws[d];
  const FrameContext& exact = frame.exact;
  // make_clip_vertex's clip mask and JIT window position, as the vertex phase formed them (built
  // in place: a default-constructed array cleared with rep stos first cost more than the copy)
  const auto corner = [&](uint32_t position) {
    const FastVertex& v = fd.vertices[position];
    return ClipVertex{draw.positions_clip[position], WindowVertex{v.x, v.y, v.z}, v.flags & kVertexClipBits, false};
  };
  const std::array<ClipVertex, 3> corners{corner(a), corner(b), corner(c)};
  const ClippedTriangles clipped = clip_triangle(corners, exact.viewport);
  for (const auto& p : clipped.triangles) {
    const std::array<WindowVertex, 3> window{p[0].window, p[1].window, p[2].window};
    if (fd.pipelined(primitive) && draw.state.cull_mode != CullMode::None &&
        pipeline_cull_drops(pipeline_cull_determinant(window), draw.state.cull_mode, draw.state.front_face))
      continue;
    FastTriangle t;
    const PieceSetup lean = setup_piece(window, encode_owner(d, primitive), fd.setup, exact.region, t);
    if (lean == PieceSetup::Drawn) piece(t);
    if (lean != PieceSetup::Full) continue;
    const TriangleSetup setup = setup_triangle(window, encode_owner(d, primitive), fd.setup);
    if (setup.fate != SetupFate::Rasterized) continue;
    if (setup.raster.binned)
      binned(setup.raster);
    else
      piece(fast_triangle_of(setup.raster, exact.region));
  }
}

// Adds the clipped triangles of blocks [begin, end) of draw d whose rows are kBlockAnyRow (and
// that some lane of which needs clipping) to `table`, in primitive order, and gives each such block
// the tile rows its lanes reach: its other lanes' corners' rows and its pieces' rectangles' rows
// (kBlockAnyRow only where a piece takes llvmpipe's wrapping set-up). Before, every worker set up
// perspective's 201 such blocks, and a worker whose rows none reached walked 11 us longer.
// Returns whether the clipping and set-up of a triangle numbered watch_from or later met a
// denormal or a tiny value (the MXCSR flags, watched over those triangles): the trailing-run check's verdict on the
// clipped triangles of those blocks (block_phases.cpp), which are the draw's clipped triangles
// there (a lane that needs clipping keeps its block at kBlockAnyRow until here).
bool clip_block_triangles(FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end, ClippedTable& table,
                          uint32_t watch_from);

// Appends an entry for each of `table`'s primitives (the next ones of the same draw) to `entries`,
// pointing into table.pieces: the table must outlive them, and its pieces must not grow.
void index_clipped(std::vector<ClippedEntry>& entries, const ClippedTable& table);

}  // namespace rastercmp::cpu::fast
