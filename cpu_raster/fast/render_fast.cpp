// render_cpu_fast: phases of a fast render (docs/performance.md; how a phase runs on the pool and
// is timed: phase_run.hpp).
//  1. frame: the exact path's frame context, the result buffers (not cleared: tiles are cleared
//     by their workers), per-draw raster state and tiles;
//  2. vertices: per fast draw, every position transformed and snapped once (in parallel);
//  3. block rows (several workers; block_phases.hpp): the tile rows each block of 8 small
//     triangles may reach, the trailing runs' denormal checks, the clipped triangles (with few
//     tasks a worker, the clip phase), and from the rows which worker draws each tile
//     (row_balance.hpp: whole rows, or runs of a heavy row's tiles in queued units); then, where
//     a row is shared between units, the tile columns of the blocks that reach it (block columns);
//     and the tile rows each primitive of the exact draws' lists may reach (list reach,
//     exact_reach.hpp);
//  4. bands: one BandWorker per worker (or per queued unit) walks all draws and rasterizes its
//     own tiles.
#include "cpu_raster/fast/render_fast.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>

#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/profile_support.hpp"
#include "cpu_raster/exact/render_exact.hpp"
#include "cpu_raster/exact/setup_methods.hpp"
#include "cpu_raster/fast/band_worker.hpp"
#include "cpu_raster/fast/block_phases.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/exact_reach.hpp"
#include "cpu_raster/fast/frame_memory.hpp"
#include "cpu_raster/fast/phase_run.hpp"
#include "cpu_raster/fast/trailing_check.hpp"
#include "cpu_raster/fast/worker_pool.hpp"
#include "model/depth_format.hpp"
#include "model/host.hpp"
#include "model/render_result.hpp"

namespace rastercmp {
namespace cpu::fast {
namespace {

constexpr size_t kVertexBlock = 4096;  // positions per task of the vertex phase

// Stored depth values keep the order the bounds rely on (tile_depth_bounds.hpp) in every draw.
bool frame_bounds_usable(const Scene& scene, const std::vector<FastDraw>& draws) {
  if (!scene.has_depth() || scene.samples != 1) return false;
  if (is_float(scene.depth_format) && !(scene.depth_clear >= 0.0f && !std::signbit(scene.depth_clear))) return false;
  if (is_float(scene.depth_format) && is_denormal(scene.depth_clear)) return false;  // read as 0 (DAZ, §7.10)
  return std::all_of(draws.begin(), draws.end(),
                     [](const FastDraw& d) { return !d.raster.depth.write || depth_values_ordered(d.raster.depth); });
}

}  // namespace

// spread_row_pitch (frame_memory.hpp) for a frame of one sample per pixel with a draw of lines and
// no draw of triangles (in such a frame, the fast draws: init_frame) whose pitched attachments fit
// kMaxPitchedBytes, its width otherwise. The thin rows' pairs (exact_rows_avx2.cpp, draw_pairs)
// are what gains from the spread rows; in a 4x frame the copy cost more than the exact rows gained
// (msaa4_grid, performance-log.md), and the fast draws' kernels take the pitch for the width.
uint32_t frame_row_pitch(const Scene& scene) {
  const bool lines = std::any_of(scene.draws.begin(), scene.draws.end(),
                                 [](const Draw& draw) { return is_line_topology(draw.topology); });
  const bool fast = std::any_of(scene.draws.begin(), scene.draws.end(),
                                [](const Draw& draw) { return is_triangle_topology(draw.topology); });
  if (scene.samples != 1 || !lines || fast) return scene.width;
  const uint32_t pitch = spread_row_pitch(scene.width);
  const size_t bytes = size_t(pitch) * scene.height * sizeof(uint32_t) * 2;  // owner and depth, one sample
  return bytes <= kMaxPitchedBytes ? pitch : scene.width;
}

namespace {

// The attachments, not cleared (the workers clear them tile by tile): `result`'s buffers, or at a
// wider row pitch the thread's pitched ones (then `result`'s are sized for the workers to pack
// the frame into: BandWorker::pack_tile_row).
void init_targets(FastFrame& frame, const Scene& scene, uint32_t pitch, RenderResult& result) {
  RenderTargets& t = frame.targets;
  frame.packed_owner = frame.packed_depth = nullptr;
  t.width = pitch;
  t.height = scene.height;
  t.samples = scene.samples;
  t.depth_format = scene.depth_format;
  const size_t count = size_t(pitch) * scene.height * scene.samples;
  if (pitch != scene.width) {
    PitchedAttachments& pitched = thread_pitched_attachments();
    t.owner = std::move(pitched.owner);
    t.depth_raw = std::move(pitched.depth);
    const size_t packed = size_t(scene.width) * scene.height * scene.samples;
    size_buffer(result.owner, packed, 0);
    frame.packed_owner = result.owner.data();
    if (scene.has_depth()) {
      size_buffer(result.depth_raw, packed, 1);
      frame.packed_depth = result.depth_raw.data();
    }
  } else {
    t.owner = std::move(result.owner);
    t.depth_raw = std::move(result.depth_raw);
  }
  size_buffer(t.owner, count, 0);
  if (scene.has_depth())
    size_buffer(t.depth_raw, count, 1);
  else
    t.depth_raw.clear();
  frame.raster.depth_clear_raw = scene.has_depth() ? clear_depth_raw(scene.depth_format, scene.depth_clear) : 0;
}

// Workers for this scene: options.threads, or 1 when a second worker would have nothing to do
// (one tile row) or too little to pay for waking it (a few thousand primitives on a small
// framebuffer: waking a thread on another, idle CPU of this VM costs 0.1-0.3 ms, measured on the
// built-in suite). The result does not depend on it.
uint32_t worker_count(const Scene& scene, uint32_t threads, const FastConfig& config) {
  if (config.every_thread) return std::max(threads, 1u);
  if (threads <= 1 || (scene.height + kTileSize - 1) / kTileSize < 2) return 1;
  uint64_t primitives = 0;
  for (const Draw& draw : scene.draws) primitives += draw.vertex_count();
  const uint64_t pixels = uint64_t(scene.width) * scene.height * scene.samples;
  return primitives < 6000 && pixels < 256 * 1024 ? 1 : threads;
}

void init_frame(FastFrame& frame, const Scene& scene, const CpuOptions& options, const FastConfig& config,
                RenderResult& result) {
  frame.scene = &scene;
  frame.exact = make_frame_context(scene, options.fma, SetupMethods{}, WorkSkips{}, options.lavapipe->rules());
  frame.workers = worker_count(scene, options.threads, config);
  frame.draws.resize(scene.draws.size());
  for (uint32_t d = 0; d < scene.draws.size(); ++d) {
    FastDraw& fd = frame.draws[d];
    const Draw& draw = scene.draws[d];
    fd.fast = scene.samples == 1 && is_triangle_topology(draw.topology);
    fd.setup = make_setup_context(frame.exact, d);
    fd.raster =
        make_draw_raster(make_depth_test_state(scene, draw, frame.exact.viewport, options.fma), false, false, false);
  }
  init_targets(frame, scene, config.spread_pitch ? frame_row_pitch(scene) : scene.width, result);
  const bool bounds = frame_bounds_usable(scene, frame.draws);
  const bool avx2 = config.allow_avx2 && host_has_avx2_fma();
  const bool avx512 = avx2 && config.allow_avx512 && host_has_avx512();
  for (FastDraw& fd : frame.draws) fd.raster = make_draw_raster(fd.raster.depth, bounds, avx2, avx512);
  FrameRaster& raster = frame.raster;
  // the pitch for the width: only the exact draws' rows and the clears use it where they differ
  raster.target = TileTarget{frame.targets.owner.data(), scene.has_depth() ? frame.targets.depth_raw.data() : nullptr,
                             int32_t(frame.targets.width), int32_t(scene.height), int32_t(scene.samples)};
  raster.tiles_x = int32_t((scene.width + kTileSize - 1) / kTileSize);
  raster.tiles_y = int32_t((scene.height + kTileSize - 1) / kTileSize);
  raster.avx2 = avx2;
  raster.avx512 = avx512;
  raster.small_setup = avx512 ? setup_small_block_avx512 : avx2 ? setup_small_block_avx2 : nullptr;
  raster.small_pair_setup = avx512 ? setup_small_pair_avx512 : nullptr;
  raster.bounds = bounds;
  const uint32_t clear = raster.depth_clear_raw;
  TileState tile;
  tile.bounds = TileBounds{clear, clear, bounds ? BoundsState::Exact : BoundsState::Unknown};
  frame.tiles.assign(size_t(raster.tiles_x) * size_t(raster.tiles_y), tile);
  for (size_t i = 0; i < frame.tiles.size(); ++i)  // row r to worker r % workers, until balance_tile_rows
    frame.tiles[i].worker = uint32_t(i / size_t(raster.tiles_x)) % frame.workers;
  raster.tiles = frame.tiles.data();
}

// Chunks a task of the chunk-flag phase scans: perspective's 235 chunks make 30 tasks.
constexpr uint32_t kChunkFlagTask = 8;

// The §1.5 chunk flags of the draws in `draws` (transformed_pipelined_chunks), per draw (empty for
// the others). With several workers in a phase of their own, each task scanning kChunkFlagTask
// chunks of one draw: every scan reads index lines and rows cold, which on one thread held 18-25 us
// of perspective's serial part at 16 workers (docs/performance-log.md).
std::vector<std::vector<bool>> flag_chunks(FastFrame& frame, const std::vector<uint32_t>& draws) {
  std::vector<std::vector<bool>> flags(frame.draws.size());
  if (draws.empty()) return flags;
  if (frame.workers == 1) {
    for (uint32_t d : draws) flags[d] = transformed_pipelined_chunks(frame, d);
    return flags;
  }
  struct ChunkTask {
    uint32_t draw, begin, end;
  };
  std::vector<std::vector<uint8_t>> bytes(frame.draws.size());  // one byte a chunk: tasks write apart
  std::vector<ChunkTask> tasks;
  for (uint32_t d : draws) {
    const uint32_t chunks = chunk_count(frame.scene->draws[d]);
    bytes[d].assign(chunks, 0);
    for (uint32_t c = 0; c < chunks; c += kChunkFlagTask) tasks.push_back({d, c, std::min(chunks, c + kChunkFlagTask)});
  }
  std::atomic<size_t> next{0};
  TaskTimes times(frame, tasks.size());
  run_phase(frame, "chunk flags", tasks.size() <= 1 ? 1 : frame.workers, [&](uint32_t w) {
    for (size_t i = next++; i < tasks.size(); i = next++)
      times.run(i, w, [&] {
        const ChunkTask& t = tasks[i];
        transformed_pipelined_chunk_range(frame, t.draw, t.begin, t.end, bytes[t.draw].data());
      });
  });
  times.attach(frame);
  for (uint32_t d : draws) flags[d].assign(bytes[d].begin(), bytes[d].end());
  return flags;
}

// Positions [begin, end) of one draw, transformed by one call of the vertex pass.
struct VertexPiece {
  uint32_t draw;
  size_t begin, end;
  uint32_t flags = 0;  // OR of the vertices' flags
};

// A task of the vertex phase: pieces [first, last), at most kVertexBlock positions in all, so that
// the small draws of a scene of many draws share one task instead of taking one each.
struct VertexTask {
  size_t first, last;
};

// Phase 2: every fast draw's positions transformed and snapped, in blocks shared out between the
// workers. With several workers, worker 0 first runs the profile check but its index scans
// (check_pending) while the others start on the vertices, which read no index: everything that
// does comes after this phase, and the scans come later (check_index_ranges, the block-row phase).
// With several workers the trailing runs' denormal checks are returned, for the block-row phase
// to share out; with one they are made here.
std::vector<TrailingCheck> transform_all_vertices(FastFrame& frame, bool check_pending) {
  // every draw of triangles or lines: the fast draws, and those the exact front end walks
  // (BandWorker::walk_exact reads their lines' and unclipped triangles' window positions here
  // instead of transforming each corner per worker)
  const auto transformed = [&frame](uint32_t d) {
    const Topology topology = frame.scene->draws[d].topology;
    return is_triangle_topology(topology) || is_line_topology(topology);
  };
  // each draw's vertices from a 64-byte line (VertexScratch): its pass stores them within lines
  constexpr size_t kLineVertices = VertexScratch::kAlignment / sizeof(FastVertex);
  const auto padded = [](size_t n) { return (n + kLineVertices - 1) / kLineVertices * kLineVertices; };
  static_assert(kVertexBlock % kLineVertices == 0);
  size_t total = 0;
  for (uint32_t d = 0; d < frame.draws.size(); ++d)
    if (transformed(d)) total += padded(frame.scene->draws[d].positions_clip.size());
  FastVertex* scratch = thread_vertex_scratch().acquire(total);
  int16_t* rows = thread_row_scratch(total);
  std::vector<VertexPiece> pieces;
  std::vector<VertexTask> tasks;
  size_t filled = kVertexBlock;  // positions in the last task, each piece's rounded up to a line
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    if (!transformed(d)) continue;
    const size_t n = frame.scene->draws[d].positions_clip.size();
    frame.draws[d].vertices = scratch;
    frame.draws[d].tile_rows = rows;
    scratch += padded(n);
    rows += n;
    for (size_t b = 0; b < n;) {
      if (filled == kVertexBlock) {
        tasks.push_back({pieces.size(), pieces.size()});
        filled = 0;
      }
      const size_t e = std::min(n, b + (kVertexBlock - filled));
      pieces.push_back({d, b, e});
      tasks.back().last = pieces.size();
      filled += padded(e - b);  // a multiple of kLineVertices: a draw split between tasks at a line
      b = e;
    }
  }
  const auto run = [&frame, &pieces](const VertexTask& task) {
    for (size_t i = task.first; i < task.last; ++i) {
      VertexPiece& piece = pieces[i];
      const Draw& draw = frame.scene->draws[piece.draw];
      const VertexJob job{draw.positions_clip.data(), frame.exact.viewport, frame.exact.fma,
                          draw.state.depth_clip_enabled()};
      FastDraw& fd = frame.draws[piece.draw];
      const auto pass = frame.raster.avx512 ? transform_vertices_avx512
                        : frame.raster.avx2 ? transform_vertices_avx2
                                            : transform_vertices_scalar;
      piece.flags = pass(job, piece.begin, piece.end, fd.vertices, fd.tile_rows);
    }
  };
  std::atomic<size_t> next{0};
  TaskTimes times(frame, tasks.size());
  run_phase(frame, "vertices", tasks.size() <= 1 ? 1 : frame.workers, [&](uint32_t w) {
    if (w == 0 && check_pending) check_lavapipe_profile_support_but_indices(*frame.scene);
    for (size_t i = next++; i < tasks.size(); i = next++) times.run(i, w, [&] { run(tasks[i]); });
  });
  times.attach(frame);
  std::vector<uint32_t> draw_flags(frame.draws.size(), 0);
  for (const VertexPiece& piece : pieces) draw_flags[piece.draw] |= piece.flags;
  // the §1.5 chunk flags, from the vertices' clip bits: the trailing run's (below) and the
  // pipeline path's cull's
  const auto any_clipped = [&](uint32_t d) { return (draw_flags[d] & kVertexClipBits) != 0; };
  const auto culled = [&](uint32_t d) { return frame.scene->draws[d].state.cull_mode != CullMode::None; };
  std::vector<uint32_t> flagged;
  for (uint32_t d = 0; d < frame.draws.size(); ++d)
    if (frame.draws[d].fast && any_clipped(d) && (frame.draws[d].setup.depth_active() || culled(d)))
      flagged.push_back(d);
  std::vector<std::vector<bool>> chunk_flags = flag_chunks(frame, flagged);
  std::vector<TrailingCheck> checks;
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    FastDraw& fd = frame.draws[d];
    if (!fd.fast) continue;
    const Draw& draw = frame.scene->draws[d];
    fd.chunk_size = primitives_per_chunk(draw);
    fd.pipelined_chunks.clear();
    const bool clipped = any_clipped(d), cull = culled(d);
    std::vector<bool> pipelined = std::move(chunk_flags[d]);  // empty where no flag is read below
    // A draw whose last chunks take the draw pipeline has those primitives set up outside lavapipe's
    // denormal mode (SetupDenormals, front_end.hpp). The fast path sets up in the mode; where that
    // can change a set-up, the exact front end draws the draw. With several workers the run's
    // set-ups are checked in the block-row phase (drop_fast_draw then); the draw is taken as fast
    // until then.
    if (clipped && fd.setup.depth_active()) {
      const uint32_t first = transformed_trailing_run(frame, d, pipelined).first, count = primitive_count(draw);
      const bool met = first < count && (depth_bias_is_denormal(draw.state.depth_bias) ||
                                         (!check_pending && run_meets_denormals(frame, d, first, count)));
      if (met) {
        fd.fast = false;
        continue;
      }
      if (check_pending && first < count) checks.push_back({d, first});
    }
    if (clipped && cull) fd.pipelined_chunks = std::move(pipelined);  // read only for that cull
    // The eight-wide set-up leaves out what it does not model: depth bias, the pipeline float cull.
    fd.small_blocks =
        fd.raster.small_fn && fd.raster.vector_ok && !draw.state.depth_bias.enable && !(fd.any_pipelined() && cull);
  }
  return checks;
}

// Phase 4: every worker walks every draw into its own tiles; with queued units (balance_tiles),
// each worker takes the next unit from the queue and walks every draw into that unit's tiles, until
// none is left.
void run_workers(FastFrame& frame) {
  if (frame.queued_units == 0) {
    // each worker's finish, from the phase's start: its pace, for the next render's rows
    const bool paced = frame.worker_work.size() == frame.workers && frame.workers > 1 && frame.profile == nullptr;
    std::vector<double> finished(frame.workers, 0.0);
    const auto start = std::chrono::steady_clock::now();
    run_phase(frame, "bands", frame.workers, [&](uint32_t w) {
      BandWorker(frame, w).run();
      if (paced) finished[w] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    });
    if (paced) worker_pool(frame.workers).record_pace(frame.worker_work, finished);
    return;
  }
  std::atomic<uint32_t> next{0};
  TaskTimes times(frame, frame.queued_units);
  run_phase(frame, "bands", frame.workers, [&](uint32_t w) {
    for (uint32_t u = next++; u < frame.queued_units; u = next++) times.run(u, w, [&] { BandWorker(frame, u).run(); });
  });
  times.attach(frame);
}

// A frame drawn at a wider row pitch than its width: the workers have packed its pixels into
// `result`'s buffers (BandWorker::pack_tile_row); the pitched buffers are kept for the next such
// frame on this thread.
void finish_pitched(FastFrame& frame, RenderResult& result) {
  RenderTargets& t = frame.targets;
  PitchedAttachments& pitched = thread_pitched_attachments();
  pitched.owner = std::move(t.owner);
  pitched.depth = std::move(t.depth_raw);
  t.width = frame.scene->width;  // the sizes move_into_result records
  t.owner = std::move(result.owner);
  t.depth_raw = std::move(result.depth_raw);
  if (!frame.scene->has_depth()) t.depth_raw.clear();
}

}  // namespace

void render_fast_into(const Scene& scene, const CpuOptions& options, const FastConfig& config, RenderResult& result) {
  if (options.profile != CpuProfile::Lavapipe || !options.methods.empty()) {
    result = render_exact(scene, options);  // the set-up method switches live in the exact path only
    return;
  }
  if (config.profile) *config.profile = RenderProfile{};
  const double start = config.profile ? thread_cpu_seconds() : 0.0;
  // The sizes first (they decide the allocations); with several workers the check runs beside
  // the vertex phase, and the index scans later, folded into the block-row phase where it reads
  // them (an index buffer is read once instead of twice before the walks).
  const bool sizes_ok = scene.width >= 1 && scene.width <= kMaxFramebufferSide && scene.height >= 1 &&
                        scene.height <= kMaxFramebufferSide && (scene.samples == 1 || scene.samples == 4) &&
                        scene.draws.size() <= kMaxDraws;
  const bool several = sizes_ok && worker_count(scene, options.threads, config) > 1;
  if (!several) check_lavapipe_profile_support(scene);
  const bool check_pending = several;
  const DenormalsFlushed ftz_daz;  // as the exact path; the pool sets it in its jobs (rules §7.10)
  FastFrame frame;
  frame.profile = config.profile;
  frame.profile_threads = config.profile_threads;
  frame.serial_mark = start;
  init_frame(frame, scene, options, config, result);
  const std::vector<TrailingCheck> checks = transform_all_vertices(frame, check_pending);
  if (check_pending) {
    check_index_ranges(frame);
    measure_all_block_rows(frame, checks);
    measure_shared_columns(frame);
    measure_list_reach(frame);
  }
  run_workers(frame);
  if (frame.failure.error) std::rethrow_exception(frame.failure.error);
  if (frame.packed_owner) finish_pitched(frame, result);
  move_into_result(std::move(frame.targets), lavapipe_profile_device(options), options.fma, result);
  if (config.profile) config.profile->serial_seconds += profiled_seconds(frame.serial_mark, thread_cpu_seconds());
}

// render_fast_side_by_side's queue order: a vertex weighs as much as this many samples' clears.
constexpr uint64_t kSideBySideVertexWeight = 16;

std::vector<size_t> side_by_side_queue(const std::vector<Scene>& scenes, const CpuOptions& options,
                                       const FastConfig& config) {
  std::vector<size_t> queued;
  if (options.threads <= 1) return queued;
  for (size_t i = 0; i < scenes.size(); ++i)
    if (worker_count(scenes[i], options.threads, config) == 1) queued.push_back(i);
  // the longest first (longest processing time first): an estimate, each sample's clear and
  // each vertex's share of the set-up (any order gives the same bytes)
  const auto estimate = [&](size_t i) {
    uint64_t vertices = 0;
    for (const Draw& draw : scenes[i].draws) vertices += draw.vertex_count();
    return uint64_t(scenes[i].width) * scenes[i].height * scenes[i].samples + kSideBySideVertexWeight * vertices;
  };
  std::stable_sort(queued.begin(), queued.end(), [&](size_t a, size_t b) { return estimate(a) > estimate(b); });
  return queued;
}

void render_fast_side_by_side(const std::vector<Scene>& scenes, const CpuOptions& options, const FastConfig& config,
                              std::vector<RenderResult>& results, std::vector<RenderProfile>* profiles) {
  results.resize(scenes.size());
  if (profiles) profiles->assign(scenes.size(), RenderProfile{});
  const auto config_of = [&](size_t i) {
    FastConfig c = config;
    c.profile = profiles ? &(*profiles)[i] : nullptr;
    return c;
  };
  const std::vector<size_t> queued = side_by_side_queue(scenes, options, config);
  std::vector<bool> in_queue(scenes.size(), false);
  for (const size_t i : queued) in_queue[i] = true;
  for (size_t i = 0; i < scenes.size(); ++i)
    if (!in_queue[i]) render_fast_into(scenes[i], options, config_of(i), results[i]);
  CpuOptions one = options;
  one.threads = 1;
  uint32_t threads = uint32_t(std::min<size_t>(std::max(options.threads, 1u), queued.size()));
  if (profiles && config.profile_threads > 0) threads = std::min(threads, config.profile_threads);
  std::atomic<size_t> next{0};
  const std::function<void(uint32_t)> job = [&](uint32_t) {
    for (size_t k = next++; k < queued.size(); k = next++) render_fast_into(scenes[queued[k]], one, config_of(queued[k]), results[queued[k]]);
  };
  if (threads <= 1)
    job(0);
  else
    worker_pool(threads).run(job);
}

RenderResult render_fast(const Scene& scene, const CpuOptions& options, const FastConfig& config) {
  RenderResult result;
  render_fast_into(scene, options, config, result);
  return result;
}

}  // namespace cpu::fast

namespace {
cpu::fast::FastConfig config_of(const CpuOptions& options) {
  cpu::fast::FastConfig config;
  config.every_thread = options.every_worker;
  return config;
}
}  // namespace

RenderResult render_cpu_fast(const Scene& scene, const CpuOptions& options) {
  return cpu::fast::render_fast(scene, options, config_of(options));
}

void render_cpu_fast_into(const Scene& scene, const CpuOptions& options, RenderResult& result) {
  cpu::fast::render_fast_into(scene, options, config_of(options), result);
}

}  // namespace rastercmp
