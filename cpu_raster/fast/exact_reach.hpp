// Where each primitive of an exact draw's list may reach (band_worker_exact.cpp's walk): the tile
// rows its visit rectangle can touch, from the vertex phase's window positions and clip bits,
// worked out once per frame for every worker instead of by each worker for every primitive.
//
// A primitive's rows are settled when every vertex lies inside every clip plane (the clipper passes
// it unchanged, so these window positions are set-up's input), is finite, and the whole spans less
// than 32000 px in x plus y with the margin (its edges stay in llvmpipe's direct range: no wrapping
// set-up, lavapipe-rules §7.5) and lies within 1e7 px of the origin in y. Its visit then lies in
// the pixel rows [floor(y_lo - margin), floor(y_hi + margin)], with `margin` how far a visit
// reaches past its vertices (reach_margin).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "cpu_raster/exact/clip_line.hpp"
#include "cpu_raster/exact/clip_test.hpp"
#include "cpu_raster/fast/fast_frame.hpp"
#include "cpu_raster/fast/fast_vertices.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::fast {

// How far a primitive's visit rectangle reaches past its vertices' window y: a line's quad its
// half width, a Bresenham end's shift (at most one pixel) and the rounded-up box; a triangle's
// box and the multisample scissor quirk one row each.
inline float reach_margin(const Draw& draw, bool lines) {
  return lines ? std::max(draw.state.line_width, 1.0f) + 3.0f : 2.0f;
}

// The pixel rows a primitive's visit may reach; settled false: not known from its vertices.
struct RowSpan {
  bool settled = false;
  int32_t lo = 0, hi = 0;
};

// vertex(k) gives corner k's window position and clip bits.
template <class Vertex>
RowSpan row_span_of(uint32_t count, float margin, Vertex&& vertex) {
  const WindowVertex first = vertex(0).first;
  float x_lo = first.x, x_hi = x_lo, y_lo = first.y, y_hi = y_lo;
  for (uint32_t k = 0; k < count; ++k) {
    const auto [window, clip_mask] = vertex(k);
    if (clip_mask != 0 || !std::isfinite(window.x) || !std::isfinite(window.y)) return {};
    x_lo = std::min(x_lo, window.x);
    x_hi = std::max(x_hi, window.x);
    y_lo = std::min(y_lo, window.y);
    y_hi = std::max(y_hi, window.y);
  }
  if ((x_hi - x_lo) + (y_hi - y_lo) + 4.0f * margin >= 32000.0f || y_lo < -1e7f || y_hi > 1e7f) return {};
  // floor of a float within +-2e7: its truncation, one less when that lies above it
  const auto floor_of = [](float value) {
    const int32_t t = int32_t(value);
    return float(t) > value ? t - 1 : t;
  };
  return {true, floor_of(y_lo - margin), floor_of(y_hi + margin)};
}

// Primitive i of a line or triangle list (`corners` a primitive) from the vertex phase's values at
// its positions; not settled when one lies past the draw's positions or the list ends before its
// last corner.
RowSpan listed_row_span(const Draw& draw, const FastVertex* transformed, size_t positions, uint32_t corners, uint32_t i,
                        float margin);

// A list primitive's tile rows as the reach phase stores them (FastDraw::list_reach): kReachUnsettled,
// or the first and last tile row, each clamped to [-1, tiles_y] and stored plus one in 16 bits.
// Clamping changes no answer: the rows of a worker lie in [0, tiles_y), and a span below row 0
// or from tiles_y on is out of the frame either way.
inline constexpr uint32_t kReachUnsettled = 0xFFFFFFFFu;
inline uint32_t pack_tile_rows(const RowSpan& span, int32_t tiles_y) {
  if (!span.settled) return kReachUnsettled;
  const auto tile = [tiles_y](int32_t row) { return uint32_t(std::clamp(row >> kTileOrder, -1, tiles_y) + 1); };
  return tile(span.lo) << 16 | tile(span.hi);
}
inline std::pair<int32_t, int32_t> unpack_tile_rows(uint32_t packed) {
  return {int32_t(packed >> 16) - 1, int32_t(packed & 0xFFFFu) - 1};
}

// How the walk clips a line of `draw` (band_worker_exact.cpp, clip_line's arguments): the planes it
// tests on every line (none while the clip skip is on: then only a line with a clip bit is
// clipped) and the x and y planes' rule of the release.
struct LineClipping {
  uint32_t inside_planes = 0;
  LineXyClip xy = LineXyClip::Clip;
};
inline LineClipping line_clipping(const FrameContext& frame, const Draw& draw) {
  return {frame.skips.clip_only_when_needed ? 0 : tested_clip_planes(draw.state.depth_clip_enabled()),
          frame.rules.has(LavapipeRule::LineGuardBand) ? LineXyClip::GuardBand : LineXyClip::Clip};
}

// The reach phase's entry for line i of a line list whose corners do not settle its rows because
// one lies outside a clip plane (listed_row_span unsettled, both corners among the positions): the
// walk's clip_line on the same corners, then the tile rows of what it leaves (pack_tile_rows of
// row_span_of on the cut ends, which set-up takes), or for a line it drops rows below the frame,
// which no worker owns (the walk then leaves it out when its set-up would be flushed, and
// otherwise clips it away itself). kReachUnsettled for a line without a clip bit, one the clipper
// passes whole, or a corner past the positions: the walk works those out as before.
uint32_t clipped_line_reach(const FrameContext& frame, const Draw& draw, const FastVertex* transformed,
                            size_t positions, uint32_t i, float margin, int32_t tiles_y);

// pack_tile_rows(listed_row_span(...)) of lines [begin, end) of a line list without indices, for
// `vertices` holding at least 2 * end positions (call only when host_has_avx2_fma()): eight lines a
// step, each lane row_span_of's operations on its two corners (the clip bits and finiteness, the
// minimum and maximum, the span's two subtractions and two adds in their order, the bounds, the
// floors by truncation) and pack_tile_rows' shift and clamp. Unit test
// FastListReach.EightLinesAtOnceGiveTheScalarAnswers.
void line_list_reach_avx2(const FastVertex* vertices, uint32_t begin, uint32_t end, float margin, int32_t tiles_y,
                          uint32_t* reach);

// The reach phase (several workers): FastDraw::list_reach of every line or triangle list the
// exact front end walks (not a fast draw), one entry per primitive, in tasks of primitives; left
// null (each worker then works its rows out as it walks) when those lists hold fewer primitives
// than a task.
void measure_list_reach(FastFrame& frame);

}  // namespace rastercmp::cpu::fast
