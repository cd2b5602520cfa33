// render_cpu_fast: phases of a fast render.
//  1. frame: the exact path's frame context, the result buffers (not cleared: tiles are cleared
//     by their workers), per-draw raster state and tiles;
//  2. vertices: per fast draw, every position transformed and snapped once (in parallel);
//  3. bands: one BandWorker per thread walks all draws and rasterizes its own tile rows.
#include "cpu_raster/fast/render_fast.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "cpu_raster/assemble.hpp"
#include "cpu_raster/depth_sample.hpp"
#include "cpu_raster/fast/band_worker.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/frame_memory.hpp"
#include "cpu_raster/fast/worker_pool.hpp"
#include "cpu_raster/profile_support.hpp"
#include "cpu_raster/setup_methods.hpp"
#include "model/render_result.hpp"

namespace rastercmp {
namespace cpu::fast {
namespace {

constexpr size_t kVertexBlock = 16384;  // positions per task of the vertex phase

SetupContext make_setup_context(const FrameContext& frame, uint32_t d) {
  SetupContext ctx;  // as front_end.cpp run_front_end builds it
  ctx.framebuffer = frame.framebuffer;
  ctx.region = frame.region;
  ctx.multisample = frame.multisample;
  ctx.fma = frame.fma;
  ctx.methods = frame.methods;
  ctx.depth_format = frame.scene->depth_format;
  ctx.state = &frame.scene->draws[d].state;
  ctx.draw_index = d;
  return ctx;
}

// Stored depth values keep the order the bounds rely on (tile_depth_bounds.hpp) in every draw.
bool frame_bounds_usable(const Scene& scene, const std::vector<FastDraw>& draws) {
  if (!scene.has_depth() || scene.samples != 1) return false;
  if (scene.depth_format == DepthFormat::D32Sfloat && !(scene.depth_clear >= 0.0f && !std::signbit(scene.depth_clear)))
    return false;
  return std::all_of(draws.begin(), draws.end(),
                     [](const FastDraw& d) { return !d.raster.depth.write || depth_values_ordered(d.raster.depth); });
}

// The attachments, in `result`'s buffers. Multisampled frames (drawn by the exact rasterizer
// alone) are cleared here at once; single-sampled ones tile by tile.
void init_targets(FastFrame& frame, const Scene& scene, RenderResult& result) {
  RenderTargets& t = frame.targets;
  t.width = scene.width;
  t.height = scene.height;
  t.samples = scene.samples;
  t.depth_format = scene.depth_format;
  const size_t count = size_t(scene.width) * scene.height * scene.samples;
  t.owner = std::move(result.owner);
  size_buffer(t.owner, count);
  t.depth_raw = std::move(result.depth_raw);
  if (scene.has_depth()) size_buffer(t.depth_raw, count);
  else t.depth_raw.clear();
  frame.raster.depth_clear_raw = scene.has_depth() ? clear_depth_raw(scene.depth_format, scene.depth_clear) : 0;
  if (scene.samples != 1) {
    std::fill(t.owner.begin(), t.owner.end(), kOwnerBackground);
    std::fill(t.depth_raw.begin(), t.depth_raw.end(), frame.raster.depth_clear_raw);
  }
}

void init_frame(FastFrame& frame, const Scene& scene, const CpuOptions& options, const FastConfig& config,
                RenderResult& result) {
  frame.scene = &scene;
  frame.exact = make_frame_context(scene, options.fma, SetupMethods{});
  init_targets(frame, scene, result);
  frame.workers = std::max<uint32_t>(options.threads, 1);
  frame.draws.resize(scene.draws.size());
  for (uint32_t d = 0; d < scene.draws.size(); ++d) {
    FastDraw& fd = frame.draws[d];
    const Draw& draw = scene.draws[d];
    fd.fast = scene.samples == 1 && is_triangle_topology(draw.topology);
    fd.setup = make_setup_context(frame.exact, d);
    fd.raster = make_draw_raster(make_depth_test_state(scene, draw, frame.exact.viewport, options.fma), false, false);
  }
  const bool bounds = frame_bounds_usable(scene, frame.draws);
  const bool avx2 = config.allow_avx2 && host_has_avx2_fma();
  for (FastDraw& fd : frame.draws) fd.raster = make_draw_raster(fd.raster.depth, bounds, avx2);
  FrameRaster& raster = frame.raster;
  raster.target = TileTarget{frame.targets.owner.data(), scene.has_depth() ? frame.targets.depth_raw.data() : nullptr,
                             int32_t(scene.width), int32_t(scene.height)};
  raster.tiles_x = int32_t((scene.width + kTileSize - 1) / kTileSize);
  raster.tiles_y = int32_t((scene.height + kTileSize - 1) / kTileSize);
  raster.avx2 = avx2;
  raster.bounds = bounds;
  const uint32_t clear = raster.depth_clear_raw;
  TileState tile;
  tile.bounds = TileBounds{clear, clear, bounds ? BoundsState::Exact : BoundsState::Unknown};
  tile.cleared = scene.samples != 1;
  frame.tiles.assign(size_t(raster.tiles_x) * size_t(raster.tiles_y), tile);
  raster.tiles = frame.tiles.data();
}

// The §1.5 chunk flag, for a draw some of whose positions are outside the clip volume.
bool any_used_vertex_clipped(const Draw& draw, const FastVertex* vertices) {
  for (uint32_t k = 0; k < draw.vertex_count(); ++k)
    if (vertices[draw.indices.empty() ? k : draw.indices[k]].flags & kVertexClipBits) return true;
  return false;
}

struct VertexTask {
  uint32_t draw;
  size_t begin, end;
};

void transform_all_vertices(FastFrame& frame) {
  size_t total = 0;
  for (uint32_t d = 0; d < frame.draws.size(); ++d)
    if (frame.draws[d].fast) total += frame.scene->draws[d].positions_clip.size();
  FastVertex* scratch = thread_vertex_scratch().acquire(total);
  std::vector<VertexTask> tasks;
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    if (!frame.draws[d].fast) continue;
    const size_t n = frame.scene->draws[d].positions_clip.size();
    frame.draws[d].vertices = scratch;
    scratch += n;
    for (size_t b = 0; b < n; b += kVertexBlock) tasks.push_back({d, b, std::min(n, b + kVertexBlock)});
  }
  const auto run = [&frame](const VertexTask& task) {
    const Draw& draw = frame.scene->draws[task.draw];
    const VertexJob job{draw.positions_clip.data(), frame.exact.viewport, frame.exact.fma,
                        draw.state.depth_clip_enabled()};
    FastVertex* out = frame.draws[task.draw].vertices;
    if (frame.raster.avx2) transform_vertices_avx2(job, task.begin, task.end, out);
    else transform_vertices_scalar(job, task.begin, task.end, out);
  };
  if (frame.workers == 1 || tasks.size() <= 1) {
    for (const VertexTask& task : tasks) run(task);
  } else {
    worker_pool(frame.workers).run([&](uint32_t w) {
      for (size_t i = w; i < tasks.size(); i += frame.workers) run(tasks[i]);
    });
  }
  std::vector<uint32_t> small_draws;
  size_t slots = 0;
  for (uint32_t d = 0; d < frame.draws.size(); ++d) {
    FastDraw& fd = frame.draws[d];
    if (!fd.fast) continue;
    const Draw& draw = frame.scene->draws[d];
    const bool any_outside = std::any_of(fd.vertices, fd.vertices + draw.positions_clip.size(),
                                         [](const FastVertex& v) { return (v.flags & kVertexClipBits) != 0; });
    fd.pipelined = any_outside && any_used_vertex_clipped(draw, fd.vertices);
    // The eight-wide set-up leaves out what it does not model: depth bias, the pipeline float cull.
    if (fd.raster.small_fn && fd.raster.vector_ok && !draw.state.depth_bias.enable &&
        !(fd.pipelined && draw.state.cull_mode != CullMode::None)) {
      small_draws.push_back(d);
      slots += BlockPipeline::slots_for(primitive_count(draw));
    }
  }
  SmallBlock* ring = block_scratch(slots);
  for (uint32_t d : small_draws) {
    const uint32_t primitives = primitive_count(frame.scene->draws[d]);
    frame.draws[d].pipeline = std::make_unique<BlockPipeline>(primitives, frame.workers, ring);
    ring += BlockPipeline::slots_for(primitives);
  }
}

void run_workers(FastFrame& frame) {
  if (frame.workers == 1) {
    BandWorker(frame, 0).run();
    return;
  }
  worker_pool(frame.workers).run([&frame](uint32_t w) { BandWorker(frame, w).run(); });
}

void fill_result(RenderResult& result, RenderTargets&& targets, bool fma) {
  result.backend = "cpu";  // as render_cpu.cpp fills it
  result.device = kLavapipeProfileDevice;
  result.fma = fma;
  result.width = targets.width;
  result.height = targets.height;
  result.samples = targets.samples;
  result.depth_format = targets.depth_format;
  result.owner = std::move(targets.owner);
  result.depth_raw = std::move(targets.depth_raw);
  result.coverage_class.clear();
}

}  // namespace

void render_fast_into(const Scene& scene, const CpuOptions& options, const FastConfig& config, RenderResult& result) {
  if (options.profile != CpuProfile::Lavapipe || !options.methods.empty()) {
    CpuOptions exact = options;  // the method switches and the spec profile live in the exact path only
    exact.threads = 0;
    result = render_cpu(scene, exact);
    return;
  }
  check_lavapipe_profile_support(scene);
  FastFrame frame;
  init_frame(frame, scene, options, config, result);
  transform_all_vertices(frame);
  run_workers(frame);
  fill_result(result, std::move(frame.targets), options.fma);
}

RenderResult render_fast(const Scene& scene, const CpuOptions& options, const FastConfig& config) {
  RenderResult result;
  render_fast_into(scene, options, config, result);
  return result;
}

}  // namespace cpu::fast

RenderResult render_cpu_fast(const Scene& scene, const CpuOptions& options) {
  return cpu::fast::render_fast(scene, options, cpu::fast::FastConfig{});
}

void render_cpu_fast_into(const Scene& scene, const CpuOptions& options, RenderResult& result) {
  cpu::fast::render_fast_into(scene, options, cpu::fast::FastConfig{}, result);
}

}  // namespace rastercmp
