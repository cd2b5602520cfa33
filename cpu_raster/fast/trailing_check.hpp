// The denormal check of a fast draw's trailing pipelined run (render_fast.cpp): a draw whose last
// chunks take the draw pipeline has those primitives set up outside lavapipe's denormal mode
// (SetupDenormals, front_end.hpp, rules §7.11); the fast path sets up in the mode, so where that
// can change a set-up the exact front end draws the draw. With one worker the check runs after the
// vertex phase, with several in the block-row phase's tasks.
#pragma once

#include <cstdint>
#include <vector>

#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/fast/fast_frame.hpp"

namespace rastercmp::cpu::fast {

// pipelined_chunks_by(draw, clipped) (draw_chunks.hpp) with `clipped` the vertex phase's clip bits,
// read from its compact rows (FastDraw::tile_rows: 2 bytes a position, where the FastVertex takes
// 16), each chunk's first index line asked for before the scan. A position past the draw's counts
// as unclipped: such an index makes the render throw (the profile check) before anything is drawn.
std::vector<bool> transformed_pipelined_chunks(const FastFrame& frame, uint32_t d);

// The same flags of chunks [begin, end) only, into pipelined[begin, end): a task of the chunk-flag
// phase (render_fast.cpp), which shares a draw's chunks out between the workers.
void transformed_pipelined_chunk_range(const FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end,
                                       uint8_t* pipelined);

// The draw's trailing pipelined run (front_end.hpp: trailing_pipeline_run_of) from its chunk flags
// (transformed_pipelined_chunks) and the vertex phase's clip bits, a position past the draw's
// counting as unclipped as there.
TrailingPipelineRun transformed_trailing_run(const FastFrame& frame, uint32_t d, const std::vector<bool>& pipelined);

// Whether the set-up of a primitive in [begin, end) of the draw's trailing pipelined run meets a
// denormal or a tiny value (trailing_check.cpp says how it is watched). clipped_elsewhere: the
// triangles that need clipping are left to clip_block_triangles; block_rows: the draw's measured
// block rows, whose kNoRow blocks are left out.
bool run_meets_denormals(const FastFrame& frame, uint32_t d, uint32_t begin, uint32_t end,
                         bool clipped_elsewhere = false, const uint32_t* block_rows = nullptr);

}  // namespace rastercmp::cpu::fast
