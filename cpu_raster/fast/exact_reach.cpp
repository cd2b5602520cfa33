#include "cpu_raster/fast/exact_reach.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <vector>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/fast/frame_memory.hpp"
#include "cpu_raster/fast/phase_run.hpp"

namespace rastercmp::cpu::fast {

RowSpan listed_row_span(const Draw& draw, const FastVertex* transformed, size_t positions, uint32_t corners, uint32_t i,
                        float margin) {
  std::array<uint32_t, 3> at{};
  const size_t first = size_t(corners) * i, listed = draw.indices.empty() ? positions : draw.indices.size();
  if (first + corners > listed) return {};
  for (uint32_t k = 0; k < corners; ++k) {
    at[k] = draw.indices.empty() ? uint32_t(first + k) : draw.indices[first + k];
    if (at[k] >= positions) return {};
  }
  return row_span_of(corners, margin, [&](uint32_t k) {
    const FastVertex& v = transformed[at[k]];
    return std::pair{WindowVertex{v.x, v.y, v.z}, v.flags & kVertexClipBits};
  });
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
        for (uint32_t i = task.begin; i < task.end; ++i)
          fd.list_reach[i] =
              pack_tile_rows(listed_row_span(draw, fd.vertices, positions, lines ? 2 : 3, i, margin), tiles_y);
      });
    }
  });
  times.attach(frame);
}

}  // namespace rastercmp::cpu::fast
