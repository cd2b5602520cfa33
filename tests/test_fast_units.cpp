// Unit tests of the fast path's machinery: the clears' fill, the attachments' memory, the render
// profile and its projection, the worker pool (its runs, FTZ/DAZ, the pace), the tile depth-bounds
// verdicts, the row columns of the exact rasterizer's planes, the benchmark statistics. The
// phases before the walks (vertex pass, chunk flags, list reach, block rows, row balance) are in
// test_fast_phases.cpp, the rasterizing stages (set-ups, edges, kernels) in test_fast_kernels.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

#include "bench/bench_scenes.hpp"
#include "bench/bench_stats.hpp"
#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/edge_plane.hpp"
#include "cpu_raster/exact/fixed_point.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/exact_rows.hpp"
#include "cpu_raster/fast/fast_frame.hpp"
#include "cpu_raster/fast/frame_memory.hpp"
#include "cpu_raster/fast/phase_run.hpp"
#include "cpu_raster/fast/tile_depth_bounds.hpp"
#include "cpu_raster/fast/tile_raster.hpp"
#include "cpu_raster/fast/worker_pool.hpp"
#include "model/host.hpp"
#include "tests/test_fast_support.hpp"

#ifdef RASTERCMP_SANITIZER_BUILD
#include <sanitizer/asan_interface.h>
#endif

namespace rastercmp::cpu::fast {
namespace {

// The clears' fill writes exactly [p, p + count): every length class (tail words, 8-word and
// 32-word steps, `rep stosl` from 4096 words, runs as long as a row of tiles) at every word
// alignment, and nothing before or after.
TEST(FastClear, FillWritesExactlyTheRun) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "host without AVX2/FMA: clears use std::fill_n";
  constexpr uint32_t kSentinel = 0xA5A5A5A5u, kValue = 0x3F800000u;
  const size_t counts[] = {0, 1, 7, 8, 9, 31, 32, 33, 4095, 4096, 4097, 65535, 65536, 65537, 65536 + 37};
  std::vector<uint32_t> buffer(65536 + 64 + 16);
  for (size_t count : counts) {
    for (size_t offset = 0; offset < 8; ++offset) {
      std::fill(buffer.begin(), buffer.end(), kSentinel);
      fill_words_avx2(buffer.data() + offset, count, kValue);
      for (size_t i = 0; i < buffer.size(); ++i) {
        const bool inside = i >= offset && i < offset + count;
        ASSERT_EQ(buffer[i], inside ? kValue : kSentinel) << "count " << count << " offset " << offset << " word " << i;
      }
    }
  }
}

// The attachments' colours (model/pixel_buffer.hpp): a fast render's owner buffer starts at a page
// boundary and its depth buffer half a page in, whatever buffers the result held before; the
// memory is reused while it is large enough and of the colour; copies and moves keep the values.
uintptr_t page_offset(const PixelBuffer& b) { return reinterpret_cast<uintptr_t>(b.data()) % 4096; }

TEST(FastMemory, DepthBufferTakesTheOtherHalfOfThePage) {
  PixelBuffer owner, depth;
  size_buffer(owner, 1024 * 1024, 0);
  size_buffer(depth, 1024 * 1024, 1);
  EXPECT_EQ(page_offset(owner), 0u);
  EXPECT_EQ(page_offset(depth), 2048u);
  std::iota(depth.begin(), depth.end(), 0u);
  const uint32_t* kept = depth.data();
  size_buffer(depth, 1000, 1);
  EXPECT_EQ(depth.data(), kept);
  EXPECT_EQ(depth.size(), 1000u);
  EXPECT_EQ(depth[999], 999u);
  size_buffer(owner, 1000, 1);  // the other colour: new memory
  EXPECT_EQ(page_offset(owner), 2048u);
  const PixelBuffer copy = depth;  // a copy keeps the values and the source's colour
  EXPECT_TRUE(std::equal(copy.begin(), copy.end(), depth.begin(), depth.end()));
  EXPECT_EQ(page_offset(copy), 2048u);
  PixelBuffer plain(300, 7u);
  plain = std::move(depth);  // a move takes the storage, colour and all
  EXPECT_EQ(page_offset(plain), 2048u);
  EXPECT_EQ(plain[123], 123u);

  RenderResult result;
  result.owner.assign(50, 1u);  // buffers of an earlier render, of the default colour
  result.depth_raw.assign(50, 1u);
  CpuOptions options;
  options.threads = 2;
  render_cpu_fast_into(bench::perspective_scene(20, 128), options, result);
  EXPECT_EQ(page_offset(result.owner), 0u);
  EXPECT_EQ(page_offset(result.depth_raw), 2048u);
}

// Freed blocks of kCachedMinBytes and more are kept (model/pixel_buffer.hpp) and handed out again
// for a request of their size or up to a fifth less, in either colour; a buffer of the Zero fill
// built on a kept block is zeroed; at most kCacheBlocks are kept, the oldest given back first; a
// small block or one larger than kCacheBytes is not kept.
TEST(FastMemory, FreedLargeBlocksAreKeptForTheNextRequestOfTheirSize) {
  release_kept_blocks();
  ASSERT_EQ(kept_block_count(), 0u);
  ASSERT_EQ(kept_block_bytes(), 0u);
  constexpr size_t kWords = size_t(1) << 18;  // 1 MiB
  uintptr_t page = 0;
  {
    PixelBuffer sevens;
    size_buffer(sevens, kWords, 0);
    std::fill(sevens.begin(), sevens.end(), 7u);
    page = reinterpret_cast<uintptr_t>(sevens.data());
  }
  EXPECT_EQ(kept_block_count(), 1u);
  EXPECT_GT(kept_block_bytes(), kWords * sizeof(uint32_t));
  {
    const PixelBuffer zeroed(kWords, PixelAllocator<uint32_t>(1));  // the other colour, the same block
    EXPECT_EQ(reinterpret_cast<uintptr_t>(zeroed.data()), page + 2048);
    EXPECT_EQ(kept_block_count(), 0u);
    EXPECT_TRUE(std::all_of(zeroed.begin(), zeroed.end(), [](uint32_t v) { return v == 0; }));  // not the sevens
  }
  ASSERT_EQ(kept_block_count(), 1u);
  {
    PixelBuffer half;
    size_buffer(half, kWords / 2, 0);  // half the size: not from the kept block
    EXPECT_EQ(kept_block_count(), 1u);
    PixelBuffer smaller(PixelAllocator<uint32_t>(0));
    smaller.resize(kWords - kWords / 8);  // an eighth less: the kept block serves it
    EXPECT_EQ(reinterpret_cast<uintptr_t>(smaller.data()), page);
    EXPECT_EQ(kept_block_count(), 0u);
  }
  release_kept_blocks();

  // sizes 1.5 times apart, so that no block serves another's request
  std::vector<size_t> words;
  for (size_t k = 0, w = size_t(80) << 10; k < kCacheBlocks + 2; ++k, w = w * 3 / 2) words.push_back(w);
  for (const size_t w : words) free_coloured(allocate_coloured(w * sizeof(uint32_t), 0));
  EXPECT_EQ(kept_block_count(), kCacheBlocks);
  EXPECT_LE(kept_block_bytes(), kCacheBytes);
  void* evicted = allocate_coloured(words[0] * sizeof(uint32_t), 0);  // the oldest, given back
  EXPECT_EQ(kept_block_count(), kCacheBlocks);
  void* kept = allocate_coloured(words[2] * sizeof(uint32_t), 0);  // the oldest still kept
  EXPECT_EQ(kept_block_count(), kCacheBlocks - 1);
  free_coloured(kept);
  free_coloured(evicted);
  release_kept_blocks();
  free_coloured(allocate_coloured(kCachedMinBytes / 2, 1));
  free_coloured(allocate_coloured(kCacheBytes + 1, 1));  // never touched: only its pages' mapping
  EXPECT_EQ(kept_block_count(), 0u);
}

#ifdef RASTERCMP_SANITIZER_BUILD
// Under AddressSanitizer (the sanitizer tree, built by clang) a kept block is poisoned, so that a
// read through a freed buffer is still reported, and unpoisoned when it is handed out again.
TEST(FastMemory, KeptBlocksArePoisonedUnderAddressSanitizer) {
  release_kept_blocks();
  constexpr size_t kBytes = size_t(1) << 20;
  void* data = allocate_coloured(kBytes, 0);
  const char* first = static_cast<const char*>(data);
  const char* last = first + kBytes - 1;
  EXPECT_EQ(__asan_address_is_poisoned(first), 0);
  free_coloured(data);
  ASSERT_EQ(kept_block_count(), 1u);
  EXPECT_NE(__asan_address_is_poisoned(first), 0);
  EXPECT_NE(__asan_address_is_poisoned(last), 0);
  void* again = allocate_coloured(kBytes, 0);
  ASSERT_EQ(again, data);
  EXPECT_EQ(__asan_address_is_poisoned(first), 0);
  EXPECT_EQ(__asan_address_is_poisoned(last), 0);
  free_coloured(again);
  release_kept_blocks();
}
#endif

// A render into new buffers that are given blocks another buffer left a poison value in writes
// every value itself (with the fast path's PixelFill::Unwritten nothing else does).
TEST(FastMemory, RendersIntoKeptBlocksWriteEveryValue) {
  constexpr uint32_t kPoison = 0xA5A5A5A5u;
  const bool fma = lavapipe_fuses_on_this_host();
  for (const Scene& scene : {bench::lines_scene(300, 512), bench::perspective_scene(20, 512)}) {
    for (const uint32_t threads : {1u, 2u}) {
      release_kept_blocks();
      const size_t count = size_t(scene.width) * scene.height * scene.samples;
      std::vector<uintptr_t> poisoned;  // the kept blocks' pages
      {
        PixelBuffer a, b;
        size_buffer(a, count, 0);
        size_buffer(b, count, 1);
        std::fill(a.begin(), a.end(), kPoison);
        std::fill(b.begin(), b.end(), kPoison);
        poisoned = {reinterpret_cast<uintptr_t>(a.data()) / 4096, reinterpret_cast<uintptr_t>(b.data()) / 4096};
      }
      ASSERT_EQ(kept_block_count(), 2u);
      CpuOptions options;
      options.threads = threads;
      options.fma = fma;
      const RenderResult result = render_cpu_fast(scene, options);
      std::vector<uintptr_t> taken = {reinterpret_cast<uintptr_t>(result.owner.data()) / 4096,
                                      reinterpret_cast<uintptr_t>(result.depth_raw.data()) / 4096};
      std::sort(poisoned.begin(), poisoned.end());
      std::sort(taken.begin(), taken.end());
      EXPECT_EQ(taken, poisoned) << "the result's buffers are the kept blocks";
      EXPECT_TRUE(fast_test::same_bytes(fast_test::render_exact(scene, fma), result))
          << scene.name << " at " << threads << " workers";
    }
  }
  release_kept_blocks();
}

// The fast path's new buffers are not zeroed (PixelFill::Unwritten), so it must write every value
// itself: rendered into buffers of the right sizes and colours (reused as they are, not zeroed)
// that hold a poison value, every kind of frame (a frame of lines drawn at a wider pitch and packed,
// triangles with tile rows no triangle reaches, 4x samples, layers) gives the exact path's bytes
// at one and two workers. Growth of a buffer of the default allocator, and of a copy, is zeroed.
TEST(FastMemory, NewBuffersAreLeftUnwrittenAndEveryValueIsRendered) {
  PixelBuffer fresh;
  size_buffer(fresh, 4096, 0);
  EXPECT_EQ(fresh.get_allocator().fill(), PixelFill::Unwritten);
  std::fill(fresh.begin(), fresh.end(), 1u);  // written before it is read, as the fast path does
  PixelBuffer copy = fresh;
  EXPECT_EQ(copy.get_allocator().fill(), PixelFill::Zero);
  copy.assign(100, 9u);
  copy.resize(10);
  copy.resize(100);  // within its capacity: the old nines zeroed
  EXPECT_EQ(copy[50], 0u);
  PixelBuffer plain;
  EXPECT_EQ(plain.get_allocator().fill(), PixelFill::Zero);

  constexpr uint32_t kPoison = 0xA5A5A5A5u;
  const bool fma = lavapipe_fuses_on_this_host();
  const std::vector<Scene> scenes = {bench::lines_scene(300, 512), bench::perspective_scene(20, 256),
                                     bench::msaa_grid_scene(12, 128), fast_test::layered_scene(3)};
  EXPECT_NE(frame_row_pitch(scenes[0]), scenes[0].width);  // drawn at a wider pitch, then packed
  for (const Scene& scene : scenes) {
    for (const uint32_t threads : {1u, 2u}) {
      RenderResult result;
      const size_t count = size_t(scene.width) * scene.height * scene.samples;
      size_buffer(result.owner, count, 0);
      size_buffer(result.depth_raw, count, 1);
      std::fill(result.owner.begin(), result.owner.end(), kPoison);
      std::fill(result.depth_raw.begin(), result.depth_raw.end(), kPoison);
      CpuOptions options;
      options.threads = threads;
      options.fma = fma;
      render_cpu_fast_into(scene, options, result);
      EXPECT_TRUE(fast_test::same_bytes(fast_test::render_exact(scene, fma), result))
          << scene.name << " at " << threads << " workers";
    }
  }
}

// bench --scaling --model's input: a profiled render lists its phases in order, each with one CPU
// time per worker, the tile-row walk ("bands") with work on every worker of a scene tall enough
// for all of them, and its bytes are those of the render without a profile.
TEST(FastRenderProfile, EveryPhaseHasEachWorkersTime) {
  const Scene scene = bench::grid_scene(120, 512);  // 28,800 triangles over eight tile rows
  CpuOptions options;
  options.threads = 4;
  FastConfig config;
  RenderProfile profile;
  config.profile = &profile;
  const RenderResult plain = render_fast(scene, options, FastConfig{});
  const RenderResult profiled = render_fast(scene, options, config);
  EXPECT_TRUE(fast_test::same_bytes(plain, profiled));
  std::vector<std::string> names;
  for (const PhaseTimes& phase : profile.phases) {
    names.push_back(phase.phase);
    ASSERT_EQ(phase.worker_seconds.size(), 4u) << phase.phase;
    for (const double t : phase.worker_seconds) EXPECT_GE(t, 0.0) << phase.phase;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"vertices", "block rows", "bands"}));
  for (const double t : profile.phases.back().worker_seconds) EXPECT_GT(t, 0.0);
  // The queue phases list their tasks, each run by one of the workers; the bands own their rows.
  for (const PhaseTimes& phase : profile.phases) {
    EXPECT_EQ(phase.tasks.empty(), phase.phase == "bands") << phase.phase;
    for (const TaskTime& task : phase.tasks) {
      EXPECT_LT(task.worker, 4u) << phase.phase;
      EXPECT_GE(task.seconds, 0.0) << phase.phase;
    }
  }
  EXPECT_GE(profile.serial_seconds, 0.0);
  // The serial time's parts: before each phase, and after the last.
  double before = 0;
  for (const PhaseTimes& phase : profile.phases) {
    EXPECT_GE(phase.serial_before, 0.0) << phase.phase;
    before += phase.serial_before;
  }
  EXPECT_LE(before, profile.serial_seconds);
  EXPECT_DOUBLE_EQ(profile.serial_after(), profile.serial_seconds - before);
  // One thread: the same phases on one worker, no pool; a second render refills, not appends.
  options.threads = 1;
  render_fast(scene, options, config);
  render_fast(scene, options, config);
  ASSERT_FALSE(profile.phases.empty());
  for (const PhaseTimes& phase : profile.phases) EXPECT_EQ(phase.worker_seconds.size(), 1u) << phase.phase;
  EXPECT_EQ(profile.phases.size(), 2u);  // vertices and bands: one worker measures no block rows
}

// A queue phase is projected as its queue would run on free cores: tasks in order, each to the
// first worker free, after each worker's time outside tasks; other phases: the busiest worker.
TEST(FastRenderProfile, QueuePhasesAreProjectedByListScheduling) {
  PhaseTimes owned{"bands", {1.0, 3.0, 2.0}, {}};
  EXPECT_DOUBLE_EQ(projected_seconds(owned), 3.0);
  // Here worker 0 ran every task (4 + 1 + 1 + 2) after 0.5 outside them; on two free cores: worker
  // 0 takes 4 (at 0.5), worker 1 takes 1, 1, 2 (ends at 4): 4.5.
  PhaseTimes queue{"block rows", {8.5, 0.0}, {{4.0, 0}, {1.0, 0}, {1.0, 0}, {2.0, 0}}};
  EXPECT_DOUBLE_EQ(projected_seconds(queue), 4.5);
  // One worker: the sum. No worker: nothing.
  PhaseTimes alone{"vertices", {3.0}, {{1.0, 0}, {2.0, 0}}};
  EXPECT_DOUBLE_EQ(projected_seconds(alone), 3.0);
  EXPECT_DOUBLE_EQ(projected_seconds(PhaseTimes{"vertices", {}, {}}), 0.0);
}

// The model's profile at N from several reps: each time the median of the reps'; one task a rep
// the host held up no longer sets its phase. Reps of different shapes: the median rep's profile.
TEST(FastRenderProfile, MedianProfileTakesEachTimesMedian) {
  const auto rep = [](double serial, double outlier_at, double bands) {
    RenderProfile r;
    r.serial_seconds = serial;
    PhaseTimes rows{"block rows", {1.0, 0.0}, {}};  // worker 0: 1.0 outside its tasks
    for (uint32_t i = 0; i < 4; ++i) {
      rows.tasks.push_back({i == outlier_at ? 9.0 : 1.0, i % 2});
      rows.worker_seconds[i % 2] += rows.tasks.back().seconds;
    }
    rows.serial_before = serial / 2;
    r.phases = {rows, PhaseTimes{"bands", {bands, 2.0}, {}, serial / 4}};
    return r;
  };
  const RenderProfile m = median_profile({rep(0.5, 0, 4.0), rep(0.7, 1, 5.0), rep(0.6, 2, 3.0)});
  EXPECT_DOUBLE_EQ(m.serial_seconds, 0.6);
  ASSERT_EQ(m.phases.size(), 2u);
  EXPECT_DOUBLE_EQ(m.phases[0].serial_before, 0.3);  // each part the median of the reps'
  EXPECT_DOUBLE_EQ(m.phases[1].serial_before, 0.15);
  EXPECT_DOUBLE_EQ(m.serial_after(), 0.6 - 0.3 - 0.15);
  EXPECT_EQ(m.phases[0].phase, "block rows");
  ASSERT_EQ(m.phases[0].tasks.size(), 4u);
  for (const TaskTime& task : m.phases[0].tasks) EXPECT_DOUBLE_EQ(task.seconds, 1.0);
  EXPECT_DOUBLE_EQ(m.phases[0].worker_seconds[0], 1.0);  // the time outside the tasks
  EXPECT_DOUBLE_EQ(m.phases[0].worker_seconds[1], 0.0);
  // on two free cores: worker 1 takes task 0, worker 0 (free at 1, the lower of a tie) task 1, ...
  EXPECT_EQ(schedule_phase(m.phases[0]).workers, (std::vector<uint32_t>{1, 0, 1, 0}));
  EXPECT_DOUBLE_EQ(projected_seconds(m.phases[0]), 3.0);  // each rep alone: 9 or 10
  EXPECT_DOUBLE_EQ(m.phases[1].worker_seconds[0], 4.0);
  EXPECT_DOUBLE_EQ(projected_seconds(m), 0.6 + 3.0 + 4.0);
  RenderProfile other = rep(0.1, 9, 1.0);
  other.phases.pop_back();
  const RenderProfile fallback = median_profile({rep(0.5, 9, 4.0), other, rep(0.6, 9, 6.0)});
  EXPECT_DOUBLE_EQ(projected_seconds(fallback), projected_seconds(rep(0.5, 9, 4.0)));
}

// The profile's intervals leave out the clock's own cost (a system call, about as long as a short
// task): an interval no longer than that reads 0, a longer one the rest; each task's two readings
// come out of its worker's time.
TEST(FastRenderProfile, IntervalsLeaveOutTheClocksOwnCost) {
  const double cost = thread_cpu_clock_cost();
  EXPECT_GE(cost, 0.0);
  EXPECT_LT(cost, 1e-3);
  EXPECT_EQ(cost, thread_cpu_clock_cost());  // measured once
  EXPECT_EQ(profiled_seconds(1.0, 1.0 + cost / 2), 0.0);
  EXPECT_NEAR(profiled_seconds(1.0, 1.0 + cost + 0.25), 0.25, 1e-12);
  FastFrame frame;
  RenderProfile profile;
  frame.profile = &profile;
  profile.phases.push_back(PhaseTimes{"block rows", {1.0, 2.0}, {}});
  TaskTimes times(frame, 3);
  for (size_t i = 0; i < 3; ++i) times.run(i, i == 2 ? 1u : 0u, [] {});
  times.attach(frame);
  ASSERT_EQ(profile.phases[0].tasks.size(), 3u);
  for (const TaskTime& task : profile.phases[0].tasks) EXPECT_GE(task.seconds, 0.0);
  EXPECT_NEAR(profile.phases[0].worker_seconds[0], 1.0 - 4 * cost, 1e-12);
  EXPECT_NEAR(profile.phases[0].worker_seconds[1], 2.0 - 2 * cost, 1e-12);
}

// docs/lavapipe-rules.md §7.10: every pool job runs with FTZ/DAZ, whatever mode the pool's threads
// were started in (this pool is new and started outside any render, so its threads inherit the
// caller's default mode), and the calling thread gets its own mode back.
TEST(FastWorkerPool, EveryJobFlushesDenormals) {
  ASSERT_FALSE(cpu::denormals_flushed());
  std::vector<int> flushed(7, -1);
  cpu::fast::worker_pool(7).run([&](uint32_t w) { flushed[w] = cpu::denormals_flushed() ? 1 : 0; });
  for (uint32_t w = 0; w < flushed.size(); ++w) EXPECT_EQ(flushed[w], 1) << "job " << w;
  EXPECT_FALSE(cpu::denormals_flushed());
}

// Runs back to back, some started after the threads went to sleep (past kSpinMicros: the caller,
// its job 0 done at once, then runs the jobs no thread has taken yet) and some whose last job ends
// long after the others (the caller past kCallerSpinMicros): every job index runs exactly once per
// run, whichever thread takes it, and the run returns only after all of them (a job run both by
// its thread and by the caller fails the count or hangs the run).
TEST(FastWorkerPool, EveryRunRunsEachJobOnceAndWaitsForAll) {
  constexpr uint32_t kWorkers = 5;
  cpu::fast::WorkerPool& pool = cpu::fast::worker_pool(kWorkers);
  std::vector<std::atomic<uint32_t>> runs(kWorkers);
  for (uint32_t run = 0; run < 300; ++run) {
    const bool sleepy = run % 50 == 0;
    if (sleepy) std::this_thread::sleep_for(std::chrono::microseconds(3 * cpu::fast::WorkerPool::kSpinMicros));
    pool.run([&](uint32_t w) {
      if (sleepy && w == kWorkers - 1)
        std::this_thread::sleep_for(std::chrono::microseconds(2 * cpu::fast::WorkerPool::kCallerSpinMicros));
      runs[w].fetch_add(1, std::memory_order_relaxed);
    });
    for (uint32_t w = 0; w < kWorkers; ++w) ASSERT_EQ(runs[w].load(), run + 1) << "job " << w << ", run " << run;
  }
}

// A job's exception reaches the caller once every job has returned, and the next run starts clean.
TEST(FastWorkerPool, AJobsExceptionReachesTheCaller) {
  cpu::fast::WorkerPool& pool = cpu::fast::worker_pool(4);
  std::atomic<uint32_t> finished{0};
  EXPECT_THROW(pool.run([&](uint32_t w) {
    if (w == 2) throw std::runtime_error("job 2");
    finished.fetch_add(1);
  }),
               std::runtime_error);
  EXPECT_EQ(finished.load(), 3u);
  EXPECT_NO_THROW(pool.run([&](uint32_t) { finished.fetch_add(1); }));
  EXPECT_EQ(finished.load(), 7u);
}

// The pool's pace (WorkerPool::record_pace, relative_speeds): equal until every worker is
// measured, equal while the slowest keeps kPaceEven of the fastest's rate, then each worker's rate
// over the fastest's, a slower pace taken at once and a faster one smoothed (a mean of paces),
// never below kPaceSlowest; phases shorter than kPaceMinSeconds and workers given no work are left
// out.
TEST(FastWorkerPool, PaceFromTheBandPhasesBefore) {
  WorkerPool pool(2);
  const std::vector<double> equal{1.0, 1.0};
  EXPECT_EQ(pool.relative_speeds(), equal);
  pool.record_pace({100, 0}, {0.004, 0.004});  // worker 1 given nothing: still unmeasured
  EXPECT_EQ(pool.relative_speeds(), equal);
  pool.record_pace({100, 100}, {0.004, 0.0045});  // 89% of the rate: even
  EXPECT_EQ(pool.relative_speeds(), equal);
  pool.record_pace({100, 100}, {0.0002, 0.0008});  // too short to say anything
  EXPECT_EQ(pool.relative_speeds(), equal);
  pool.record_pace({100, 100}, {0.004, 0.008});  // paces 40 and 80 us a unit: slower, at once
  std::vector<double> speeds = pool.relative_speeds();
  EXPECT_EQ(speeds[0], 1.0);
  EXPECT_NEAR(speeds[1], 0.5, 1e-9);
  pool.record_pace({100, 100}, {0.004, 0.004});  // faster: (80 + 40) / 2
  EXPECT_NEAR(pool.relative_speeds()[1], 40.0 / 60.0, 1e-9);
  pool.record_pace({100, 100}, {0.004, 0.012});  // slower: 120 at once
  EXPECT_NEAR(pool.relative_speeds()[1], 40.0 / 120.0, 1e-9);
  for (int k = 0; k < 8; ++k) pool.record_pace({100, 100}, {0.004, 0.04});  // a tenth of the rate
  speeds = pool.relative_speeds();
  EXPECT_EQ(speeds[1], WorkerPool::kPaceSlowest);
  for (int k = 0; k < 8; ++k) pool.record_pace({100, 100}, {0.004, 0.004});  // even again
  EXPECT_EQ(pool.relative_speeds(), equal);
  pool.record_pace({100, 100}, {0.004, 0.04});
  EXPECT_LT(pool.relative_speeds()[1], 1.0);
  pool.reset_pace();  // forgotten: equal until measured again
  EXPECT_EQ(pool.relative_speeds(), equal);
}

// A verdict holds for every fragment and stored value in the ranges (depth_test_passes decides).
TEST(FastDepthBounds, VerdictsHoldForEveryValueInTheRanges) {
  fast_test::Random r(5);
  for (int trial = 0; trial < 3000; ++trial) {
    const auto value = [&] { return uint32_t(r.below(12)) * 0x100000u; };  // D32 bits of floats in [0, 1)
    FragmentRange f{value(), value()};
    if (f.lo > f.hi) std::swap(f.lo, f.hi);
    TileBounds tile{value(), value(), BoundsState::Exact};
    if (tile.zmin > tile.zmax) std::swap(tile.zmin, tile.zmax);
    const CompareOp op = CompareOp(r.below(8));
    const DepthVerdict verdict = classify_depth(op, f, tile);
    if (verdict == DepthVerdict::PerPixel) continue;
    for (uint32_t a = f.lo; a <= f.hi; a += 0x100000u)
      for (uint32_t s = tile.zmin; s <= tile.zmax; s += 0x100000u)
        ASSERT_EQ(depth_test_passes(op, DepthFormat::D32Sfloat, a, s), verdict == DepthVerdict::AllPass)
            << to_string(op) << " fragment " << a << " stored " << s;
  }
}

TEST(FastDepthBounds, FragmentRangeIsTheCornersExtremes) {
  fast_test::Random r(9);
  DepthTestState depth;
  depth.active = true;
  depth.format = DepthFormat::X8D24Unorm;
  for (int trial = 0; trial < 200; ++trial) {
    FastTriangle t;
    t.a0 = float(r.range(-2, 2));
    t.dzdx = float(r.range(-0.01, 0.01));
    t.dzdy = float(r.range(-0.01, 0.01));
    const PixelRect rect{int32_t(r.below(500)), int32_t(r.below(500)), 0, 0};
    const PixelRect box{rect.x0, rect.y0, rect.x0 + int32_t(r.below(64)), rect.y0 + int32_t(r.below(64))};
    FragmentRange range;
    ASSERT_TRUE(fragment_range(t, box, depth, range));
    for (int32_t y = box.y0; y <= box.y1; ++y)
      for (int32_t x = box.x0; x <= box.x1; ++x) {
        const uint32_t raw =
            sample_depth(DepthPlane{t.a0, t.dzdx, t.dzdy}, 0, float(x), float(y), depth.range, depth.format, depth.fma)
                .raw;
        ASSERT_GE(raw, range.lo);
        ASSERT_LE(raw, range.hi);
      }
  }
  FastTriangle steep;
  steep.dzdx = std::numeric_limits<float>::infinity();
  FragmentRange unused;
  EXPECT_FALSE(fragment_range(steep, PixelRect{0, 0, 3, 3}, depth, unused));
}

// plane_columns (exact_rows.hpp) against the plane's value at every column of a row: the columns
// it keeps are exactly those with E > 0, for planes of every slope, with and without a sample offset.
TEST(FastExactRows, PlaneColumnsAreThePassingColumns) {
  fast_test::Random r(23);
  for (int n = 0; n < 4000; ++n) {
    EdgePlane plane;
    plane.dcdx = int64_t(r.below(4)) == 0 ? 0 : int64_t(r.below(1u << 20)) - (1 << 19);
    plane.dcdy = int64_t(r.below(1u << 20)) - (1 << 19);
    plane.c = (int64_t(r.below(1u << 30)) - (1 << 29)) * int64_t(1 + r.below(1u << 10));
    const int64_t sample_x = int64_t(r.below(256)), y_fixed = int64_t(r.below(1u << 16)) * 16 + int64_t(r.below(256));
    int32_t x0 = int32_t(r.below(300)) - 20, x1 = x0 + int32_t(r.below(400));
    const int32_t lo = x0, hi = x1;
    const bool any = plane_columns(plane, sample_x, y_fixed, x0, x1);
    for (int32_t px = lo; px <= hi; ++px) {
      const bool passes = edge_value(plane, int64_t(px) * kFixedOne + sample_x, y_fixed) > 0;
      ASSERT_EQ(passes, any && px >= x0 && px <= x1) << "case " << n << " column " << px;
    }
  }
}

TEST(FastBenchStats, QuartilesAndExtremes) {
  const bench::TimingStats s = bench::summarize({5, 1, 4, 2, 3});
  EXPECT_EQ(s.count, 5u);
  EXPECT_DOUBLE_EQ(s.median, 3);
  EXPECT_DOUBLE_EQ(s.q1, 2);
  EXPECT_DOUBLE_EQ(s.q3, 4);
  EXPECT_DOUBLE_EQ(s.min, 1);
  EXPECT_DOUBLE_EQ(s.max, 5);
  EXPECT_DOUBLE_EQ(bench::summarize({1, 2}).median, 1.5);
  EXPECT_EQ(bench::summarize({}).count, 0u);
}

// Keeps a block's pages in use, as far as the compiler knows (a malloc, memset and free of memory
// nothing reads may otherwise be left out).
void escape(void* p) { asm volatile("" : : "r"(p) : "memory"); }

// bench::keep_freed_memory: a block above glibc's default mmap threshold (128 KiB) and below
// kKeptBlockBytes, freed and allocated again, is not faulted in again (it would be 4,096 page
// faults mapped and unmapped each time, or trimmed off the heap's top). ASan's allocator refuses
// the settings.
TEST(FastBenchStats, FreedMemoryIsKeptForTheNextAllocation) {
  const bool kept = bench::keep_freed_memory();
#ifdef RASTERCMP_SANITIZER_BUILD
  EXPECT_FALSE(kept);
  return;
#endif
  ASSERT_TRUE(kept);
  constexpr size_t kBytes = size_t(16) << 20;
  static_assert(kBytes < size_t(bench::kKeptBlockBytes));
  void* first = std::malloc(kBytes);
  ASSERT_NE(first, nullptr);
  std::memset(first, 1, kBytes);
  escape(first);
  std::free(first);
  const long before = bench::page_fault_count();
  void* again = std::malloc(kBytes);
  ASSERT_NE(again, nullptr);
  std::memset(again, 2, kBytes);
  escape(again);
  const long faults = bench::page_fault_count() - before;
  std::free(again);
  EXPECT_LT(faults, 64) << "the block's 4,096 pages were faulted in again";
}

}  // namespace
}  // namespace rastercmp::cpu::fast
