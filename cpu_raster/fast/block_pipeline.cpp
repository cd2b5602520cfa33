#include "cpu_raster/fast/block_pipeline.hpp"

#include <algorithm>
#include <thread>

namespace rastercmp::cpu::fast {

BlockPipeline::BlockPipeline(uint32_t primitives, uint32_t workers)
    : blocks_((primitives + 7) / 8),
      slots_(std::max<uint32_t>(1, std::min(blocks_, kMaxSlots))),
      workers_(workers),
      ring_(std::make_unique<SmallBlock[]>(slots_)),
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

void wait_for_other_worker(uint32_t& rounds) {
  if (++rounds < 64) {
    __builtin_ia32_pause();
  } else {
    std::this_thread::yield();
  }
}

}  // namespace rastercmp::cpu::fast
