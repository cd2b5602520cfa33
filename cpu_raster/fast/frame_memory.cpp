#include "cpu_raster/fast/frame_memory.hpp"

#include <sys/mman.h>

#include <array>

namespace rastercmp::cpu::fast {

void advise_huge_pages(void* data, size_t bytes) {
#ifdef MADV_HUGEPAGE
  constexpr uintptr_t kHuge = uintptr_t(2) << 20;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // a hint: errors ignored
#else
  (void)data;
  (void)bytes;
#endif
}

void size_buffer(PixelBuffer& buffer, size_t count, uint32_t colour) {
  if (buffer.capacity() < count || buffer.get_allocator().colour() != colour) {
    PixelBuffer fresh{PixelAllocator<uint32_t>(colour, PixelFill::Unwritten)};
    fresh.reserve(count);  // new memory, or a kept block (pixel_buffer.hpp): the hint applies to its untouched pages
    advise_huge_pages(fresh.data(), count * sizeof(uint32_t));
    buffer = std::move(fresh);
  }
  buffer.resize(count);
}

FastVertex* VertexScratch::acquire(size_t count) {
  if (count > capacity_) {
    // FastVertex is an implicit-lifetime type: the array's elements begin their lifetime here
    data_.reset(static_cast<FastVertex*>(::operator new[](count * sizeof(FastVertex), std::align_val_t{kAlignment})));
    capacity_ = count;
    advise_huge_pages(data_.get(), count * sizeof(FastVertex));
  }
  return data_.get();
}

int16_t* thread_row_scratch(size_t count) {
  thread_local std::vector<int16_t> rows;
  // + 8: the AVX2 pass stores 8 rows at a time; the block-row gathers read 2 bytes past a position
  if (rows.size() < count + 8) rows.resize(count + 8);
  return rows.data();
}

uint32_t* thread_word_scratch(size_t count, WordScratch use) {
  thread_local std::array<std::vector<uint32_t>, 2> scratch;
  std::vector<uint32_t>& words = scratch[size_t(use)];
  if (words.size() < count) words.resize(count);
  return words.data();
}

PitchedAttachments& thread_pitched_attachments() {
  thread_local PitchedAttachments attachments;
  return attachments;
}

VertexScratch& thread_vertex_scratch() {
  thread_local VertexScratch scratch;
  return scratch;
}

}  // namespace rastercmp::cpu::fast
