// The block-row phase, its clip phase and the block-column phase (block_phases.hpp).
#include "cpu_raster/fast/block_phases.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/profile_support.hpp"
#include "cpu_raster/fast/band_worker.hpp"
#include "cpu_raster/fast/block_rows.hpp"
#include "cpu_raster/fast/clipped_pieces.hpp"
#include "cpu_raster/fast/frame_memory.hpp"
#include "cpu_raster/fast/phase_run.hpp"
#include "cpu_raster/fast/row_balance.hpp"
#include "cpu_raster/fast/trailing_check.hpp"
#include "cpu_raster/fast/worker_pool.hpp"

namespace rastercmp::cpu::fast {
namespace {

// A draw the block-row phase found a trailing set-up in that meets a denormal: the exact front end
// draws it (walk_exact), and what the phase measured for it is dropped.
void drop_fast_draw(FastDraw& fd) {
  fd.fast = false;
  fd.small_blocks = false;
  fd.block_rows = nullptr;
  fd.block_columns = nullptr;
  fd.group_rows = nullptr;
  fd.clipped.clear();
  fd.pipelined_chunks.clear();
}

struct RowTask {
  uint32_t draw, begin, end;
};

// Whether the block-row phase reads every index of the draw (a list's indices past its last
// whole triangle, or those of a draw without a primitive, belong to no block).
bool blocks_read_every_index(const FastDraw& fd, const Draw& draw) {
  const uint32_t count = primitive_count(draw);
  return fd.small_blocks && count > 0 &&
         (draw.topology != Topology::TriangleList || 3 * size_t(count) == draw.indices.size());
}

}  // namespace

void check_index_ranges(const FastFrame& frame) {
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    const Draw& draw = frame.scene->draws[d];
    if (!blocks_read_every_index(frame.draws[d], draw) && !indices_in_range(draw))
      check_lavapipe_profile_support(*frame.scene);
  }
}

namespace {

// Adds +1 at the first and -1 past the last tile row of each of n blocks to diff[0, tiles_y];
// kBlockAnyRow (every worker sets such a block up) and kNoRow count nowhere. A mesh's neighbouring
// blocks mostly reach the same rows: counted a run of equal values at a time. Returns whether some
// block is kBlockAnyRow.
bool count_block_rows(const uint32_t* block_rows, uint32_t n, size_t tiles_y, int32_t* diff) {
  bool any_row = false;
  uint32_t b = 0;
  while (b < n) {
    const uint32_t packed = block_rows[b];
    const uint32_t first = b;
    while (++b < n && block_rows[b] == packed) {
    }
    const uint32_t lo = packed & 0xFFFFu, hi = packed >> 16;
    any_row |= packed == kBlockAnyRow;
    if (packed == kBlockAnyRow || lo > hi || hi >= tiles_y) continue;
    diff[lo] += int32_t(b - first);
    diff[hi + 1] -= int32_t(b - first);
  }
  return any_row;
}

// The rows n blocks reach together (FastDraw::group_rows): kBlockAnyRow if one may reach any, the
// least lo and greatest hi of the others' rows, kNoRow if none reaches a row.
uint32_t group_tile_rows(const uint32_t* block_rows, uint32_t n) {
  uint32_t lo = 0xFFFFu, hi = 0;
  for (uint32_t b = 0; b < n; ++b) {
    const uint32_t packed = block_rows[b];
    if (packed == kBlockAnyRow) return kBlockAnyRow;
    if ((packed & 0xFFFFu) > (packed >> 16)) continue;  // kNoRow, or no row of the region
    lo = std::min(lo, packed & 0xFFFFu);
    hi = std::max(hi, packed >> 16);
  }
  return lo > hi ? kNoRow : lo | hi << 16;
}

// The workers' relative speeds for the static rows (WorkerPool::relative_speeds): equal with
// one worker and in a profiled render (the model projects from equal shares).
std::vector<double> pace_speeds(const FastFrame& frame) {
  if (frame.workers <= 1 || frame.profile != nullptr) return {};
  return worker_pool(frame.workers).relative_speeds();
}

// Which worker draws each tile, from the blocks that reach each row (`reach`: `tasks` arrays of
// tiles_y + 1 differences) and the row's width (tile_row_weight): whole rows, or runs of a heavy
// row's tiles, shared out by balance_tiles. No block reaching any row: row r to r % workers. When every draw
// is one of small blocks and each block's rows are known (`rows_known`), a row no block reaches is
// one nothing draws into (the blocks' rows hold their triangles' and pieces' rectangles). Shared out
// as whole rows, such rows go to FastFrame::unowned_rows, cleared by whichever worker finishes
// first: clearing costs more after other work (its lines come from memory) than the weights say,
// and these clears are what evens out the workers' ends (perspective after a lavapipe render: the
// sky's six rows). Where the rows are cut into queued units, each such row is a unit of its own
// (weighing its clear), at the queue's end: one worker finishing early would otherwise clear them
// all, and the queue hands them out one at a time anyway (perspective at 16 workers: the sky's six
// rows, 80 us, on one of the horizon row's units, the phase's largest).
void balance_tile_rows(FastFrame& frame, const std::vector<int32_t>& reach, size_t tasks, bool rows_known) {
  const size_t tiles_y = size_t(std::max(frame.raster.tiles_y, 0));
  std::vector<uint64_t> blocks(tiles_y, 0);  // the blocks reaching each row
  for (size_t t = 0; t < tasks; ++t) {
    int64_t running = 0;
    for (size_t r = 0; r < tiles_y; ++r) {
      running += reach[t * (tiles_y + 1) + r];
      blocks[r] += uint64_t(running);
    }
  }
  if (std::all_of(blocks.begin(), blocks.end(), [](uint64_t count) { return count == 0; })) return;
  bool unowned = rows_known && std::all_of(frame.draws.begin(), frame.draws.end(),
                                           [](const FastDraw& d) { return d.small_blocks; });
  const uint32_t tiles_x = uint32_t(std::max(frame.raster.tiles_x, 0));
  std::vector<uint64_t> weights(tiles_y, 0);
  const auto weigh = [&] {
    for (size_t r = 0; r < tiles_y; ++r)
      weights[r] = unowned && blocks[r] == 0 ? 0 : tile_row_weight(blocks[r], tiles_x);
  };
  weigh();
  if (unowned && cuts_rows(weights, tiles_x, frame.workers)) {
    unowned = false;
    weigh();
  }
  const TileUnits units = balance_tiles(weights, tiles_x, frame.workers, pace_speeds(frame));
  std::vector<int32_t> empty_rows;
  for (size_t r = 0; r < tiles_y; ++r)
    if (unowned && blocks[r] == 0) empty_rows.push_back(int32_t(r));
  for (size_t i = 0; i < frame.tiles.size(); ++i) frame.tiles[i].worker = units.unit[i];
  frame.queued_units = units.queued ? units.count : 0;
  if (!units.queued) {
    frame.worker_work.assign(frame.workers, 0.0);
    for (size_t r = 0; r < tiles_y; ++r)
      if (!(unowned && weights[r] == 0)) frame.worker_work[units.unit[r * tiles_x]] += double(weights[r]);
  }
  for (const int32_t r : empty_rows)
    for (uint32_t tx = 0; tx < tiles_x; ++tx) frame.tiles[size_t(r) * tiles_x + tx].worker = kUnownedRow;
  frame.unowned_rows = std::move(empty_rows);
}

// A frame of exact draws only (lines, multisampled frames; no block gives an estimate): worker w
// owns the w-th of `workers` runs of consecutive tile rows, so that a primitive, whose rows are
// consecutive, mostly lies in one worker's rows and the other workers leave it out before its
// set-up (BandWorker::misses_own_rows); r % workers would give a primitive crossing a row border
// to two workers. Only which thread writes a row changes.
void contiguous_rows(FastFrame& frame) {
  if (std::any_of(frame.draws.begin(), frame.draws.end(), [](const FastDraw& d) { return d.fast; })) return;
  const size_t tiles_x = size_t(std::max(frame.raster.tiles_x, 1)), tiles_y = size_t(std::max(frame.raster.tiles_y, 1));
  const std::vector<uint32_t> owner = contiguous_runs(uint32_t(tiles_y), frame.workers, pace_speeds(frame));
  for (size_t i = 0; i < frame.tiles.size(); ++i) frame.tiles[i].worker = owner[i / tiles_x];
  frame.worker_work.assign(frame.workers, 0.0);  // a row's work: one unit
  for (const uint32_t w : owner) frame.worker_work[w] += 1.0;
}

// Blocks per task of the block-row phase: about kRowTasksPerWorker tasks per worker, in whole
// groups (a task's groups are its own), at least kMinRowTaskBlocks and at most kMaxRowTaskBlocks.
// Each task has its own set-up, row counts and clipped table (merged after the phase): with two
// workers tiny_1m's 131,000 blocks make 64 tasks instead of 512, and its render at two threads
// takes 5% less. Tasks of fewer than 256 blocks did not pay at 16 workers: perspective's far-plane
// triangles fill about 30 neighbouring blocks, one task of 33-40 us however the tasks are cut (their
// clipping; the clip phase of measure_all_block_rows now shares it out).
uint32_t row_task_blocks(size_t blocks, uint32_t workers) {
  constexpr size_t kRowTasksPerWorker = 32, kMinRowTaskBlocks = 256, kMaxRowTaskBlocks = 4096;
  static_assert(kMinRowTaskBlocks % kGroupBlocks == 0 && kMaxRowTaskBlocks % kGroupBlocks == 0);
  const size_t per_task = blocks / (size_t(std::max(workers, 1u)) * kRowTasksPerWorker);
  const size_t groups = (per_task + kGroupBlocks - 1) / kGroupBlocks;
  return uint32_t(std::clamp<size_t>(groups * kGroupBlocks, kMinRowTaskBlocks, kMaxRowTaskBlocks));
}

}  // namespace

// Phase 3 (several workers): which tile rows each block of small triangles may reach, measured
// once, so that a worker sets up only the blocks it may draw into. Each block's indices are
// checked before they are read through; a bad one: the full profile check, which throws. The
// same phase checks the trailing runs' set-ups for denormals (`checks`, transform_all_vertices):
// a draw of small blocks in its row tasks, each on its own blocks once their rows are known;
// another a range of primitives per task. A draw that meets one is dropped from the fast draws
// (drop_fast_draw) and from the row balance. With few row tasks a worker, a clip phase follows
// for the row tasks with many blocks to clip (below).
void measure_all_block_rows(FastFrame& frame, const std::vector<TrailingCheck>& checks) {
  constexpr uint32_t kCheckTaskPrimitives = 2048;
  struct CheckTask {
    uint32_t draw, begin, end;
  };
  // A draw of small blocks has its run checked by the row tasks, on their blocks, after measuring
  // their rows (blocks nobody sets up left out); any other draw by check tasks.
  std::vector<CheckTask> check_tasks;
  for (const TrailingCheck& c : checks) {
    if (frame.draws[c.draw].small_blocks) continue;
    const uint32_t count = primitive_count(frame.scene->draws[c.draw]);
    for (uint32_t p = c.first; p < count; p += kCheckTaskPrimitives)
      check_tasks.push_back({c.draw, p, std::min(count, p + kCheckTaskPrimitives)});
  }
  size_t blocks = 0, groups = 0;
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    if (!frame.draws[d].small_blocks) continue;
    const size_t count = (primitive_count(frame.scene->draws[d]) + 7) / 8;
    blocks += count;
    groups += (count + kGroupBlocks - 1) / kGroupBlocks;
  }
  if (blocks == 0) contiguous_rows(frame);
  if (blocks == 0 && check_tasks.empty()) return;
  // the blocks' rows, then their columns, then their groups' rows
  uint32_t* rows = blocks > 0 ? thread_word_scratch(2 * blocks + groups, WordScratch::BlockRows) : nullptr;
  uint32_t* group_rows = blocks > 0 ? rows + 2 * blocks : nullptr;
  std::vector<RowTask> tasks;
  const uint32_t task_blocks = row_task_blocks(blocks, frame.workers);
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    if (!frame.draws[d].small_blocks) continue;
    const uint32_t count = (primitive_count(frame.scene->draws[d]) + 7) / 8;
    frame.draws[d].block_rows = rows;
    frame.draws[d].block_columns = rows + blocks;
    frame.draws[d].group_rows = group_rows;
    rows += count;
    group_rows += (count + kGroupBlocks - 1) / kGroupBlocks;
    for (uint32_t b = 0; b < count; b += task_blocks) tasks.push_back({d, b, std::min(count, b + task_blocks)});
  }
  // Per task, the blocks that reach each tile row, as differences (+1 at a block's first row, -1
  // past its last): the rows' work estimate (balance_tile_rows).
  const size_t tiles_y = size_t(std::max(frame.raster.tiles_y, 0));
  std::vector<int32_t> reach(tasks.size() * (tiles_y + 1), 0);
  std::vector<ClippedTable> clipped(tasks.size());  // the tasks' clipped triangles (clipped_pieces.hpp)
  std::vector<uint8_t> met(check_tasks.size(), 0), row_met(tasks.size(), 0);
  // A draw of small blocks has its clipped triangles watched where the row tasks clip them, from
  // its trailing run's first on; the check tasks leave them out.
  std::vector<uint32_t> watch_from(frame.draws.size(), UINT32_MAX);
  for (const TrailingCheck& c : checks) watch_from[c.draw] = c.first;
  // A row task clips the triangles of its kBlockAnyRow blocks (a corner needs clipping) itself.
  // With fewer than kClipPhaseTasksPerWorker row tasks a worker, one task's clipping can outlast
  // the rest of the phase (perspective at 16 workers: 2.5 tasks a worker, one of them 33-40 us of
  // far-plane clipping, the others about 3-14): there a row task clips its first
  // kInPlaceClipBlocks such blocks and leaves the rest (from deferred_from[t] on) to the clip phase
  // below. With more tasks a worker (perspective at 2 workers: 20) the extra phase cost more than it saved.
  constexpr size_t kClipPhaseTasksPerWorker = 8;
  constexpr uint32_t kInPlaceClipBlocks = 8;
  const uint32_t in_place_blocks =
      tasks.size() < kClipPhaseTasksPerWorker * size_t(frame.workers) ? kInPlaceClipBlocks : UINT32_MAX;
  std::vector<uint32_t> deferred_from(tasks.size(), UINT32_MAX);
  std::atomic<size_t> next{0};
  std::atomic<bool> bad_index{false}, any_row{false};
  // Blocks [begin, end) of row task t after their rows are measured: the clipped triangles (which
  // narrow kBlockAnyRow) into `table`, the trailing run's check on their primitives.
  const auto clip_and_check = [&](size_t t, uint32_t begin, uint32_t end, ClippedTable& table) {
    const RowTask& task = tasks[t];
    bool found = clip_block_triangles(frame, task.draw, begin, end, table, watch_from[task.draw]);
    const uint32_t run_first = watch_from[task.draw];  // the trailing run's check on these blocks
    if (run_first != UINT32_MAX) {
      const uint32_t lo = std::max(run_first, begin * 8);
      const uint32_t hi = std::min(primitive_count(frame.scene->draws[task.draw]), end * 8);
      found |= lo < hi && run_meets_denormals(frame, task.draw, lo, hi, true, frame.draws[task.draw].block_rows);
    }
    return found;
  };
  // Row task t's groups and row counts, once every block's rows are final.
  const auto finish_rows = [&](size_t t) {
    const RowTask& task = tasks[t];
    const uint32_t* block_rows = frame.draws[task.draw].block_rows;
    uint32_t* groups_of_draw = frame.draws[task.draw].group_rows;
    for (uint32_t g = task.begin; g < task.end; g += kGroupBlocks)
      groups_of_draw[g / kGroupBlocks] = group_tile_rows(block_rows + g, std::min(kGroupBlocks, task.end - g));
    if (count_block_rows(block_rows + task.begin, task.end - task.begin, tiles_y, reach.data() + t * (tiles_y + 1)))
      any_row = true;
  };
  TaskTimes times(frame, check_tasks.size() + tasks.size());
  const auto row_task = [&](size_t t) {
    const RowTask& task = tasks[t];
    std::fill(frame.draws[task.draw].block_columns + task.begin, frame.draws[task.draw].block_columns + task.end,
              kColumnsUnknown);
    if (!measure_block_rows(frame, task.draw, task.begin, task.end)) {
      bad_index = true;
      return;
    }
    const uint32_t* block_rows = frame.draws[task.draw].block_rows;
    uint32_t in_place_end = task.end;
    for (uint32_t b = task.begin, any = 0; b < task.end; ++b) {
      if (block_rows[b] == kBlockAnyRow && ++any > in_place_blocks) {
        in_place_end = b;
        break;
      }
    }
    if (clip_and_check(t, task.begin, in_place_end, clipped[t])) row_met[t] = 1;
    if (in_place_end < task.end)
      deferred_from[t] = in_place_end;
    else
      finish_rows(t);
  };
  run_phase(frame, "block rows", frame.workers, [&](uint32_t w) {
    for (size_t i = next++; i < check_tasks.size() + tasks.size(); i = next++) {
      times.run(i, w, [&] {
        if (i < check_tasks.size()) {  // the checks first: the longer tasks
          const CheckTask& c = check_tasks[i];
          met[i] = run_meets_denormals(frame, c.draw, c.begin, c.end, frame.draws[c.draw].small_blocks) ? 1 : 0;
        } else {
          row_task(i - check_tasks.size());
        }
      });
    }
  });
  times.attach(frame);
  if (bad_index) check_lavapipe_profile_support(*frame.scene);
  // The clip phase: the rest of each such row task's blocks cut into clip tasks of at most
  // kClipTaskBlocks kBlockAnyRow blocks (perspective's far-plane triangles fill about 30
  // neighbouring blocks: one row task's clipping took 33-40 us of a 16-worker block-row phase); the
  // last of a row task's clip tasks to finish forms its groups and row counts.
  constexpr uint32_t kClipTaskBlocks = 4;
  struct ClipTask {
    uint32_t row_task, begin, end;
  };
  std::vector<ClipTask> clip_tasks;
  std::vector<std::atomic<uint32_t>> pending(tasks.size());
  for (size_t t = 0; t < tasks.size(); ++t) {
    if (deferred_from[t] == UINT32_MAX) continue;
    const RowTask& task = tasks[t];
    const uint32_t* block_rows = frame.draws[task.draw].block_rows;
    uint32_t begin = deferred_from[t], any = 0;
    for (uint32_t b = begin; b < task.end; ++b) {
      if (block_rows[b] != kBlockAnyRow || ++any < kClipTaskBlocks) continue;
      clip_tasks.push_back({uint32_t(t), begin, b + 1});
      begin = b + 1;
      any = 0;
    }
    if (begin < task.end) clip_tasks.push_back({uint32_t(t), begin, task.end});
  }
  for (const ClipTask& c : clip_tasks) pending[c.row_task].fetch_add(1, std::memory_order_relaxed);
  std::vector<ClippedTable> clip_tables(clip_tasks.size());  // the clip tasks' clipped triangles
  std::vector<uint8_t> clip_met(clip_tasks.size(), 0);
  if (!clip_tasks.empty()) {
    std::atomic<size_t> next_clip{0};
    TaskTimes clip_times(frame, clip_tasks.size());
    run_phase(frame, "clipped blocks", frame.workers, [&](uint32_t w) {
      for (size_t i = next_clip++; i < clip_tasks.size(); i = next_clip++) {
        clip_times.run(i, w, [&] {
          const ClipTask& c = clip_tasks[i];
          if (clip_and_check(c.row_task, c.begin, c.end, clip_tables[i])) clip_met[i] = 1;
          // the last clip task of its row task sees every other one's block rows (acq_rel)
          if (pending[c.row_task].fetch_sub(1, std::memory_order_acq_rel) == 1) finish_rows(c.row_task);
        });
      }
    });
    clip_times.attach(frame);
  }
  for (size_t i = 0; i < check_tasks.size(); ++i)
    if (met[i]) drop_fast_draw(frame.draws[check_tasks[i].draw]);
  for (size_t t = 0; t < tasks.size(); ++t)
    if (row_met[t]) drop_fast_draw(frame.draws[tasks[t].draw]);
  for (size_t i = 0; i < clip_tasks.size(); ++i)
    if (clip_met[i]) drop_fast_draw(frame.draws[tasks[clip_tasks[i].row_task].draw]);
  // the clipped triangles in primitive order: each row task's own, then its clip tasks' (each
  // draw's entries sized first); their pieces stay in the tasks' tables, which the frame keeps
  // (moving a table keeps its pieces where they are). Copying the pieces together took 8-11 us of
  // the serial part at 16 workers (perspective's 614 clipped triangles: about 900 pieces of 60
  // bytes, written on other cores).
  std::vector<size_t> entries(frame.draws.size(), 0);
  for (size_t t = 0; t < tasks.size(); ++t) entries[tasks[t].draw] += clipped[t].primitives.size();
  for (size_t i = 0; i < clip_tasks.size(); ++i)
    entries[tasks[clip_tasks[i].row_task].draw] += clip_tables[i].primitives.size();
  for (uint32_t d = 0; d < frame.draws.size(); ++d)
    if (frame.draws[d].small_blocks && entries[d] > 0)
      frame.draws[d].clipped.reserve(frame.draws[d].clipped.size() + entries[d]);
  for (size_t t = 0, i = 0; t < tasks.size(); ++t) {
    FastDraw& fd = frame.draws[tasks[t].draw];
    if (!fd.small_blocks)  // dropped: its blocks count nowhere
      std::fill_n(reach.begin() + std::ptrdiff_t(t * (tiles_y + 1)), tiles_y + 1, 0);
    else
      index_clipped(fd.clipped, clipped[t]);
    for (; i < clip_tasks.size() && clip_tasks[i].row_task == t; ++i)
      if (fd.small_blocks) index_clipped(fd.clipped, clip_tables[i]);
  }
  frame.clipped_tables.reserve(frame.clipped_tables.size() + clipped.size() + clip_tables.size());
  for (ClippedTable& table : clipped) frame.clipped_tables.push_back(std::move(table));
  for (ClippedTable& table : clip_tables) frame.clipped_tables.push_back(std::move(table));
  balance_tile_rows(frame, reach, tasks.size(), !any_row);
}

// Phase 3b (queued units, several of them in a tile row): the tile columns of every block that
// reaches such a shared row (measure_block_columns), worked out once before the walks, where
// each unit of the row that meets the block would otherwise work them out, all of them at once
// on as many cores. A task whose groups reach no shared row is left out.
void measure_shared_columns(FastFrame& frame) {
  constexpr uint32_t kColumnTaskBlocks = 256;
  if (frame.queued_units == 0) return;
  const size_t tiles_x = size_t(std::max(frame.raster.tiles_x, 0)), tiles_y = size_t(std::max(frame.raster.tiles_y, 0));
  std::vector<uint32_t> shared_before(tiles_y + 1, 0);
  for (size_t r = 0; r < tiles_y; ++r) {
    const TileState* row = frame.tiles.data() + r * tiles_x;
    const bool shared = std::any_of(row, row + tiles_x, [row](const TileState& t) { return t.worker != row[0].worker; });
    shared_before[r + 1] = shared_before[r] + (shared ? 1 : 0);
  }
  if (shared_before[tiles_y] == 0) return;
  const auto meets_shared = [&](uint32_t rows) {
    if (rows == kBlockAnyRow) return true;
    const TileRowRange r = rows_in_frame(rows, int32_t(tiles_y));
    return r.lo <= r.hi && shared_before[size_t(r.hi) + 1] != shared_before[size_t(r.lo)];
  };
  std::vector<RowTask> tasks;
  static_assert(kColumnTaskBlocks % kGroupBlocks == 0, "a task's groups are its own");
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    const FastDraw& fd = frame.draws[d];
    if (!fd.small_blocks) continue;  // block_columns and group_rows are set with its block rows
    const uint32_t count = (primitive_count(frame.scene->draws[d]) + 7) / 8;
    for (uint32_t b = 0; b < count; b += kColumnTaskBlocks) {
      const uint32_t end = std::min(count, b + kColumnTaskBlocks);
      bool meets = false;
      for (uint32_t g = b; g < end && !meets; g += kGroupBlocks) meets = meets_shared(fd.group_rows[g / kGroupBlocks]);
      if (meets) tasks.push_back({d, b, end});
    }
  }
  if (tasks.empty()) return;
  std::atomic<size_t> next{0};
  TaskTimes times(frame, tasks.size());
  run_phase(frame, "block columns", frame.workers, [&](uint32_t w) {
    for (size_t i = next++; i < tasks.size(); i = next++)
      times.run(i, w, [&] { measure_block_columns(frame, tasks[i].draw, tasks[i].begin, tasks[i].end, shared_before); });
  });
  times.attach(frame);
}

}  // namespace rastercmp::cpu::fast
