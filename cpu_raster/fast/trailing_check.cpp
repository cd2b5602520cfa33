#include "cpu_raster/fast/trailing_check.hpp"

#include <array>
#include <vector>

#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/fast/block_rows.hpp"
#include "cpu_raster/fast/clipped_pieces.hpp"
#include "cpu_raster/fast/fast_vertices.hpp"
#include "cpu_raster/fast/small_block_input.hpp"
#include "cpu_raster/fast/small_triangles.hpp"

namespace rastercmp::cpu::fast {

namespace {

// The vertex phase's clip bits of a position, from its compact rows (FastDraw::tile_rows).
struct RowClipped {
  const int16_t* rows;
  size_t positions;
  bool operator()(uint32_t position) const { return position < positions && row_clip_bits(rows[position]) != 0; }
};

// Each chunk's scan mostly stops within its first few vertices, each chunk's first index line
// read cold: the lines of chunks [begin, end) asked for at once, before the scan waits on them
// one by one.
void prefetch_chunk_indices(const Draw& draw, uint32_t begin, uint32_t end) {
  if (draw.indices.empty()) return;
  const uint32_t per_chunk = primitives_per_chunk(draw);
  for (uint32_t c = begin; c < end; ++c)
    __builtin_prefetch(draw.indices.data() + chunk_vertices(draw.topology, c * per_chunk, c * per_chunk).begin);
}

}  // namespace

std::vector<bool> transformed_pipelined_chunks(const FastFrame& frame, uint32_t d) {
  const Draw& draw = frame.scene->draws[d];
  prefetch_chunk_indices(draw, 0, chunk_count(draw));
  return pipelined_chunks_by(draw, RowClipped{frame.draws[d].tile_rows, draw.positions_clip.size()});
}

void transformed_pipelined_chunk_range(const FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end,
                                       uint8_t* pipelined) {
  const Draw& draw = frame.scene->draws[d];
  prefetch_chunk_indices(draw, begin, end);
  const RowClipped clipped{frame.draws[d].tile_rows, draw.positions_clip.size()};
  for (uint32_t c = begin; c < end; ++c) pipelined[c] = chunk_pipelined_by(draw, c, clipped) ? 1 : 0;
}

TrailingPipelineRun transformed_trailing_run(const FastFrame& frame, uint32_t d, const std::vector<bool>& pipelined) {
  const FastDraw& fd = frame.draws[d];
  const Draw& draw = frame.scene->draws[d];
  const size_t positions = draw.positions_clip.size();
  const auto clipped = [&fd, positions](uint32_t position) {
    return position < positions && (fd.vertices[position].flags & kVertexClipBits) != 0;
  };
  return trailing_pipeline_run_of(draw, pipelined, clipped);
}

namespace {

// Whether the set-up of a primitive in [begin, end) of the draw's trailing pipelined run meets a
// denormal or a tiny value: the clip and set-up of each, watched (DenormalWatch, this thread's
// flags). Both vertex orders of an unclipped triangle are tried (set-up may swap two vertices).
// False: every set-up of the range gives the same bits with denormals flushed and kept. Primitives
// with a position past the draw's are left out (the render throws on them). On AVX2 hosts, without
// depth bias, the unclipped triangles' planes are formed eight at a time, in one order
// (trailing_depth_planes_avx2: each lane the scalar operations, so the same flags, which the other
// order raises too; a last group of fewer repeats its first triangle). With clipped_elsewhere the
// triangles that need clipping are left to clip_block_triangles, which watches them as it clips
// them (the block-row phase). With block_rows (the draw's measured block rows, the same phase) the
// triangles of a block at kNoRow are left out: every one of them is outside one clip plane (the
// clipper drops it) or has its corners' rows outside the draw region's (its set-up stops at the
// region test, before the depth plane: setup_triangle, place_in_region), so none forms a plane.
// ByBlockRows is a template argument because a test in the loop slowed the one-worker check,
// which runs without block rows (its serial time 0.21-0.22 -> 0.24-0.27 ms, perspective).
template <Topology T, bool Indexed, bool ByBlockRows>
bool run_meets_denormals_of(const FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end, bool clipped_elsewhere,
                            const uint32_t* block_rows) {
  const FastDraw& fd = frame.draws[d];
  const Draw& draw = frame.scene->draws[d];
  const uint32_t* indices = draw.indices.data();
  const size_t positions = draw.positions_clip.size();
  const DepthBias& bias = draw.state.depth_bias;
  const UnormBiasUnits units = unorm_bias_units(fd.setup.rules);
  const bool eight_wide = frame.raster.avx2 && !bias.enable;
  const auto window = [&](uint32_t position) {
    const FastVertex& v = fd.vertices[position];
    return WindowVertex{v.x, v.y, v.z};
  };
  // The results are stored where the compiler cannot drop the arithmetic that forms them.
  volatile float sink = 0.0f;
  volatile uint32_t sink_bits = 0;
  const auto keep = [&sink](const DepthPlane& p, float offset) {
    sink = p.a0;
    sink = p.dzdx;
    sink = p.dzdy;
    sink = offset;
  };
  const auto keep_eight = [&sink_bits](uint32_t sign_bits) { sink_bits = sign_bits; };
  alignas(32) uint32_t group[3][8];
  uint32_t grouped = 0;
  const DenormalWatch watch;
  for (uint32_t i = begin; i < end; ++i) {
    if constexpr (ByBlockRows) {
      if (block_rows[i / 8] == kNoRow) {
        i |= 7;  // the block's last primitive
        continue;
      }
    }
    const std::array<uint32_t, 3> n = vertex_numbers<T>(i);
    const uint32_t a = Indexed ? indices[n[0]] : n[0], b = Indexed ? indices[n[1]] : n[1],
                   c = Indexed ? indices[n[2]] : n[2];
    if (a >= positions || b >= positions || c >= positions) continue;
    const uint32_t flags = fd.vertices[a].flags | fd.vertices[b].flags | fd.vertices[c].flags;
    if (flags & kVertexClipBits) {
      if (!clipped_elsewhere && needs_clipping(fd.vertices[a].flags, fd.vertices[b].flags, fd.vertices[c].flags))
        for_each_piece(
            frame, d, i, a, b, c, [&](const FastTriangle& t) { keep(DepthPlane{t.a0, t.dzdx, t.dzdy}, t.offset); },
            [&](const RasterPrimitive& p) { keep(p.depth, p.offset.offset); });
      continue;
    }
    if (flags & kVertexSnapFailed) continue;
    if (eight_wide) {
      group[0][grouped] = a;
      group[1][grouped] = b;
      group[2][grouped] = c;
      if (++grouped == 8) {
        keep_eight(trailing_depth_planes_avx2(fd.vertices, group));
        grouped = 0;
      }
      continue;
    }
    for (const std::array<WindowVertex, 3>& v :
         {std::array<WindowVertex, 3>{window(a), window(b), window(c)},
          std::array<WindowVertex, 3>{window(a), window(c), window(b)}}) {
      keep(triangle_depth_plane(v, 0.5f),
           bias.enable ? triangle_depth_offset(v, bias, fd.setup.depth_format, true, units).offset : 0.0f);
    }
  }
  if (grouped > 0) {
    for (uint32_t l = grouped; l < 8; ++l)
      for (uint32_t k = 0; k < 3; ++k) group[k][l] = group[k][0];
    keep_eight(trailing_depth_planes_avx2(fd.vertices, group));
  }
  return watch.met();
}

}  // namespace

bool run_meets_denormals(const FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end, bool clipped_elsewhere,
                         const uint32_t* block_rows) {
  return on_triangle_layout(
      frame.scene->draws[d],
      [&](auto topology, auto indexed) {
        return block_rows != nullptr
                   ? run_meets_denormals_of<topology(), indexed(), true>(frame, d, begin, end, clipped_elsewhere,
                                                                         block_rows)
                   : run_meets_denormals_of<topology(), indexed(), false>(frame, d, begin, end, clipped_elsewhere,
                                                                          nullptr);
      },
      [] { return true; });  // not a fast draw: fast draws are triangle draws
}

}  // namespace rastercmp::cpu::fast
