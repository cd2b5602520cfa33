#include "cpu_raster/fast/block_pipeline.hpp"

#include <algorithm>
#include <thread>

namespace rastercmp::cpu::fast {

uint32_t BlockPipeline::slots_for(uint32_t primitives) {
  return std::max<uint32_t>(1, std::min((primitives + 7) / 8, kMaxSlots));
}

BlockPipeline::BlockPipeline(uint32_t primitives, uint32_t workers, SmallBlock* ring)
    : blocks_((primitives + 7) / 8),
      slots_(slots_for(primitives)),
      workers_(workers),
      ring_(ring),
      ready_(std::make_unique<Counter[]>(slots_)),
      consumed_(std::make_unique<Counter[]>(workers)) {}

int64_t BlockPipeline::claim() {
  uint32_t next = next_.value.load(std::memory_order_relaxed);
  for (;;) {
    if (next >= blocks_) return -1;
    uint32_t slowest = UINT32_MAX;
    for (uint32_t w = 0; w < workers_; ++w)
      slowest = std::min(slowest, consumed_[w].value.load(std::memory_order_acquire));
    if (next >= slowest + slots_) return -1;  // its slot still holds a block someone has to draw
    if (next_.value.compare_exchange_weak(next, next + 1, std::memory_order_acq_rel)) return next;
  }
}

SmallBlock* block_scratch(size_t count) {
  thread_local std::unique_ptr<SmallBlock[]> storage;
  thread_local size_t capacity = 0;
  if (count > capacity) {
    storage = std::make_unique<SmallBlock[]>(count);
    capacity = count;
  }
  return storage.get();
}

void wait_for_other_worker(uint32_t& rounds) {
  if (++rounds < 32) {
    __builtin_ia32_pause();
  } else {
    std::this_thread::yield();
  }
}

}  // namespace rastercmp::cpu::fast
