// The small-triangle pipeline of one draw (docs/performance.md "Threads"): the draw's primitives
// are cut into blocks of 8; any worker claims the next block, sets it up once
// (setup_small_block_avx2) into a ring slot and publishes it; every worker then draws the
// published blocks in order, each into its own tile rows. So the set-up work is shared instead
// of repeated by every worker, and the order per pixel is still the submission order.
// A slot is reused only when every worker has drawn its block; workers run concurrently
// (worker_pool.hpp), so a worker that waits for a slot or a block always gets it eventually.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

#include "cpu_raster/fast/small_triangles.hpp"

namespace rastercmp::cpu::fast {

struct SmallBlock {
  uint32_t first = 0;  // first primitive of the block
  SmallBlockInput in;
  SmallBlockOutput out;
};

class BlockPipeline {
 public:
  // `ring` holds slots_for(primitives) blocks (block_scratch), reused from render to render.
  BlockPipeline(uint32_t primitives, uint32_t workers, SmallBlock* ring);
  static uint32_t slots_for(uint32_t primitives);

  uint32_t blocks() const { return blocks_; }
  // The next block to set up, or -1 when all are taken or the ring is full.
  int64_t claim();
  SmallBlock& slot(uint32_t block) { return ring_[block % slots_]; }
  void publish(uint32_t block) { ready_[block % slots_].value.store(block + 1, std::memory_order_release); }
  bool ready(uint32_t block) const {
    return ready_[block % slots_].value.load(std::memory_order_acquire) == block + 1;
  }
  // `worker` has drawn blocks [0, count).
  void consumed(uint32_t worker, uint32_t count) { consumed_[worker].value.store(count, std::memory_order_release); }

  static constexpr uint32_t kMaxSlots = 128;

 private:
  struct alignas(64) Counter {
    std::atomic<uint32_t> value{0};
  };
  uint32_t blocks_, slots_, workers_;
  SmallBlock* ring_;
  std::unique_ptr<Counter[]> ready_;
  std::unique_ptr<Counter[]> consumed_;
  Counter next_;
};

// A short wait for another worker: spin first, then give the core away.
void wait_for_other_worker(uint32_t& rounds);

// The calling thread's ring storage: at least `count` blocks, valid until the next call.
SmallBlock* block_scratch(size_t count);

}  // namespace rastercmp::cpu::fast
