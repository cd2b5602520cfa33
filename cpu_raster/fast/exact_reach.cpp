#include "cpu_raster/fast/exact_reach.hpp"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <vector>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/frame_memory.hpp"
#include "cpu_raster/fast/phase_run.hpp"

namespace rastercmp::cpu::fast {

namespace {

// Primitive i's corners of a list (`corners` a primitive): the positions corners * i + k, or the
// indices there; false when the list ends before its last corner or one lies past the positions.
bool listed_corners(const Draw& draw, size_t positions, uint32_t corners, uint32_t i, std::array<uint32_t, 3>& at) {
  const size_t first = size_t(corners) * i, listed = draw.indices.empty() ? positions : draw.indices.size();
  if (first + corners > listed) return false;
  for (uint32_t k = 0; k < corners; ++k) {
    at[k] = draw.indices.empty() ? uint32_t(first + k) : draw.indices[first + k];
    if (at[k] >= positions) return false;
  }
  return true;
}

}  // namespace

RowSpan listed_row_span(const Draw& draw, const FastVertex* transformed, size_t positions, uint32_t corners, uint32_t i,
                        float margin) {
  std::array<uint32_t, 3> at{};
  if (!listed_corners(draw, positions, corners, i, at)) return {};
  return row_span_of(corners, margin, [&](uint32_t k) {
    const FastVertex& v = transformed[at[k]];
    return std::pair{WindowVertex{v.x, v.y, v.z}, v.flags & kVertexClipBits};
  });
}

uint32_t clipped_line_reach(const FrameContext& frame, const Draw& draw, const FastVertex* transformed,
                            size_t positions, uint32_t i, float margin, int32_t tiles_y) {
  std::array<uint32_t, 3> at{};
  if (!listed_corners(draw, positions, 2, i, at)) return kReachUnsettled;
  std::array<ClipVertex, 2> corner;
  uint32_t bits = 0;
  for (uint32_t k = 0; k < 2; ++k) {
    const FastVertex& v = transformed[at[k]];
    corner[k] = ClipVertex{draw.positions_clip[at[k]], WindowVertex{v.x, v.y, v.z}, v.flags & kVertexClipBits, false};
    bits |= corner[k].clip_mask;
  }
  if (bits == 0) return kReachUnsettled;  // not settled for another reason: left to the walk
  const LineClipping clipping = line_clipping(frame, draw);
  const ClippedLine clipped = clip_line(corner, frame.viewport, clipping.inside_planes, clipping.xy);
  if (clipped.fate == ClipFate::Outside || clipped.fate == ClipFate::Discarded)
    return pack_tile_rows(RowSpan{true, -kTileSize, -1}, tiles_y);  // tile rows [-1, -1]: no frame row
  if (clipped.fate != ClipFate::Clipped) return kReachUnsettled;
  const auto end = [&clipped](uint32_t k) { return std::pair{clipped.line[k].window, 0u}; };
  return pack_tile_rows(row_span_of(2, margin, end), tiles_y);
}

namespace {

// Per lane: a float whose exponent is all ones (infinite or NaN).
RASTERCMP_AVX2 inline __m256i not_finite8(__m256 v) {
  const __m256i exponent = _mm256_set1_epi32(0x7F800000);
  return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_castps_si256(v), exponent), exponent);
}

// row_span_of's floor_of per lane: the truncation, one less where it lies above the value.
RASTERCMP_AVX2 inline __m256i floor8(__m256 v) {
  const __m256i t = _mm256_cvttps_epi32(v);
  return _mm256_add_epi32(t, _mm256_castps_si256(_mm256_cmp_ps(_mm256_cvtepi32_ps(t), v, _CMP_GT_OQ)));
}

// pack_tile_rows' tile per lane: the row's tile row clamped to [-1, tiles_y], plus one.
RASTERCMP_AVX2 inline __m256i packed_tile8(__m256i row, int32_t tiles_y) {
  const __m256i tile = _mm256_srai_epi32(row, kTileOrder);
  return _mm256_add_epi32(_mm256_min_epi32(_mm256_max_epi32(tile, _mm256_set1_epi32(-1)), _mm256_set1_epi32(tiles_y)),
                          _mm256_set1_epi32(1));
}

}  // namespace

RASTERCMP_AVX2 void line_list_reach_avx2(const FastVertex* vertices, uint32_t begin, uint32_t end, float margin,
                                         int32_t tiles_y, uint32_t* reach) {
  static_assert(sizeof(FastVertex) == 8 * sizeof(float) / 2, "a line's two corners: eight floats");
  const __m256 four_margins = _mm256_set1_ps(4.0f * margin), margins = _mm256_set1_ps(margin);  // 4 * m: exact
  const __m256 span_bound = _mm256_set1_ps(32000.0f), y_bound = _mm256_set1_ps(1e7f);
  const __m256i clip_bits = _mm256_set1_epi32(int32_t(kVertexClipBits)), all = _mm256_set1_epi32(-1);
  uint32_t i = begin;
  for (; i + 8 <= end; i += 8) {
    // lines i .. i + 7, each two corners of four floats: transposed so that register c holds
    // component c of every line (x0, y0, z0, flags0, x1, y1, z1, flags1)
    const float* p = reinterpret_cast<const float*>(vertices + 2 * size_t(i));
    __m256 r[8];
    for (int k = 0; k < 8; ++k) r[k] = _mm256_loadu_ps(p + 8 * k);
    const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);
    const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
    const __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]), t5 = _mm256_unpackhi_ps(r[4], r[5]);
    const __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]), t7 = _mm256_unpackhi_ps(r[6], r[7]);
    const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
    const __m256 u3 = _mm256_shuffle_ps(t1, t3, 0xEE);  // (the z components are not read)
    const __m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xEE);
    const __m256 u7 = _mm256_shuffle_ps(t5, t7, 0xEE);
    const __m256 x0 = _mm256_permute2f128_ps(u0, u4, 0x20), y0 = _mm256_permute2f128_ps(u1, u5, 0x20);
    const __m256 f0 = _mm256_permute2f128_ps(u3, u7, 0x20), x1 = _mm256_permute2f128_ps(u0, u4, 0x31);
    const __m256 y1 = _mm256_permute2f128_ps(u1, u5, 0x31), f1 = _mm256_permute2f128_ps(u3, u7, 0x31);
    const __m256i flags = _mm256_or_si256(_mm256_castps_si256(f0), _mm256_castps_si256(f1));
    // every lane of a line not settled all ones: kReachUnsettled once or-ed into its packed rows
    __m256i unsettled =
        _mm256_xor_si256(_mm256_cmpeq_epi32(_mm256_and_si256(flags, clip_bits), _mm256_setzero_si256()), all);
    unsettled = _mm256_or_si256(unsettled, _mm256_or_si256(_mm256_or_si256(not_finite8(x0), not_finite8(y0)),
                                                           _mm256_or_si256(not_finite8(x1), not_finite8(y1))));
    const __m256 x_lo = _mm256_min_ps(x0, x1), x_hi = _mm256_max_ps(x0, x1);
    const __m256 y_lo = _mm256_min_ps(y0, y1), y_hi = _mm256_max_ps(y0, y1);
    const __m256 span =
        _mm256_add_ps(_mm256_add_ps(_mm256_sub_ps(x_hi, x_lo), _mm256_sub_ps(y_hi, y_lo)), four_margins);
    const __m256 out =
        _mm256_or_ps(_mm256_cmp_ps(span, span_bound, _CMP_GE_OQ),
                     _mm256_or_ps(_mm256_cmp_ps(y_lo, _mm256_sub_ps(_mm256_setzero_ps(), y_bound), _CMP_LT_OQ),
                                  _mm256_cmp_ps(y_hi, y_bound, _CMP_GT_OQ)));
    unsettled = _mm256_or_si256(unsettled, _mm256_castps_si256(out));
    const __m256i lo = packed_tile8(floor8(_mm256_sub_ps(y_lo, margins)), tiles_y);
    const __m256i hi = packed_tile8(floor8(_mm256_add_ps(y_hi, margins)), tiles_y);
    const __m256i packed = _mm256_or_si256(_mm256_slli_epi32(lo, 16), hi);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(reach + i), _mm256_or_si256(packed, unsettled));
  }
  for (; i < end; ++i) {  // the last lines, one by one
    const auto corner = [&](uint32_t k) {
      const FastVertex& v = vertices[2 * size_t(i) + k];
      return std::pair{WindowVertex{v.x, v.y, v.z}, v.flags & kVertexClipBits};
    };
    reach[i] = pack_tile_rows(row_span_of(2, margin, corner), tiles_y);
  }
}

void measure_list_reach(FastFrame& frame) {
  constexpr uint32_t kTaskPrimitives = 4096;  // a primitive takes about 10 ns
  struct Task {
    uint32_t draw, begin, end;
  };
  const auto listed = [&frame](uint32_t d) {
    const Topology topology = frame.scene->draws[d].topology;
    return !frame.draws[d].fast && frame.draws[d].vertices != nullptr &&
           (topology == Topology::LineList || topology == Topology::TriangleList);
  };
  std::vector<Task> tasks;
  size_t total = 0;
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    if (!listed(d)) continue;
    const uint32_t count = primitive_count(frame.scene->draws[d]);
    for (uint32_t b = 0; b < count; b += kTaskPrimitives) tasks.push_back({d, b, std::min(count, b + kTaskPrimitives)});
    total += count;
  }
  // Fewer than a task's primitives: each worker works out its own as it walks (under 40 us), and
  // the phase's hand-out would cost about as much.
  if (total < kTaskPrimitives) {
    for (FastDraw& fd : frame.draws) fd.list_reach = nullptr;
    return;
  }
  uint32_t* reach = thread_word_scratch(total, WordScratch::ListReach);
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    frame.draws[d].list_reach = listed(d) ? reach : nullptr;
    if (listed(d)) reach += primitive_count(frame.scene->draws[d]);
  }
  const int32_t tiles_y = frame.raster.tiles_y;
  std::atomic<size_t> next{0};
  TaskTimes times(frame, tasks.size());
  run_phase(frame, "list reach", frame.workers, [&](uint32_t w) {
    for (size_t t = next++; t < tasks.size(); t = next++) {
      times.run(t, w, [&] {
        const Task& task = tasks[t];
        const Draw& draw = frame.scene->draws[task.draw];
        const FastDraw& fd = frame.draws[task.draw];
        const bool lines = draw.topology == Topology::LineList;
        const float margin = reach_margin(draw, lines);
        const size_t positions = draw.positions_clip.size();
        // a line list without indices whose positions hold the task's lines: eight at a time
        if (lines && draw.indices.empty() && frame.raster.avx2 && 2 * size_t(task.end) <= positions) {
          line_list_reach_avx2(fd.vertices, task.begin, task.end, margin, tiles_y, fd.list_reach);
        } else {
          for (uint32_t i = task.begin; i < task.end; ++i)
            fd.list_reach[i] =
                pack_tile_rows(listed_row_span(draw, fd.vertices, positions, lines ? 2 : 3, i, margin), tiles_y);
        }
        if (!lines) return;
        // the lines a clip plane cuts: clipped once here rather than by every worker
        for (uint32_t i = task.begin; i < task.end; ++i)
          if (fd.list_reach[i] == kReachUnsettled)
            fd.list_reach[i] = clipped_line_reach(frame.exact, draw, fd.vertices, positions, i, margin, tiles_y);
      });
    }
  });
  times.attach(frame);
}

}  // namespace rastercmp::cpu::fast
