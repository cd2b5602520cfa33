#include "model/pixel_buffer.hpp"

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>

// AddressSanitizer's presence: GCC defines __SANITIZE_ADDRESS__, clang answers __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define RASTERCMP_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RASTERCMP_ASAN 1
#endif
#endif

#if defined(RASTERCMP_ASAN)
#include <sanitizer/asan_interface.h>
#define RASTERCMP_POISON(p, n) ASAN_POISON_MEMORY_REGION(p, n)
#define RASTERCMP_UNPOISON(p, n) ASAN_UNPOISON_MEMORY_REGION(p, n)
#else
#define RASTERCMP_POISON(p, n) ((void)(p), (void)(n))
#define RASTERCMP_UNPOISON(p, n) ((void)(p), (void)(n))
#endif

namespace rastercmp {
namespace {

constexpr uintptr_t kPage = 4096;
constexpr uintptr_t kHalfPage = kPage / 2;
constexpr size_t kHeader = 2 * sizeof(void*);  // the block's start and size, just before the storage

// The block of `size` bytes at `start` (malloc's): its storage for `colour`, with the header
// written. The storage begins at the first page boundary at least kHeader past `start` (malloc's
// 16-byte alignment puts that boundary at most kPage past it), plus the colour's half page, so it
// ends by start + bytes + kPage + kHalfPage.
void* storage_of(void* start, size_t size, uint32_t colour) {
  const uintptr_t page = (reinterpret_cast<uintptr_t>(start) + kHeader + kPage - 1) & ~(kPage - 1);
  void* data = reinterpret_cast<void*>(page + (colour & 1u) * kHalfPage);
  std::memcpy(static_cast<char*>(data) - sizeof(void*), &start, sizeof(void*));
  std::memcpy(static_cast<char*>(data) - 2 * sizeof(void*), &size, sizeof(size));
  return data;
}

// Freed blocks of at least kCachedMinBytes, kept for the next request of about their size. A
// render's attachments are large, and a process that renders frame after frame (the bench's renders
// into new buffers, the experiments' sweeps) frees and asks for blocks of the same sizes; glibc
// serves each such request with a fresh mmap (a freed mmapped block raises its mmap threshold to
// that block's size, which a request of the same size still meets) and gives it back with munmap,
// so every render faulted its attachments' pages in again and had the kernel clear them
// (perspective into new buffers at two threads 7.8-7.9 ms against 1.2 into reused ones, on a host
// where a page's first touch took about 10 us; docs/performance-log.md, "Freed attachments kept for
// the next render"). At most kCacheBlocks blocks and kCacheBytes bytes are kept, the oldest given
// back first. A kept block's bytes are what its last owner left: PixelAllocator's Zero fill writes
// every element of a new buffer, so only PixelFill::Unwritten buffers see them, and those are
// written before they are read. Under AddressSanitizer a kept block is poisoned, so a read
// through a freed buffer is still reported.
class BlockCache {
 public:
  // The smallest kept block of `size` to `size` + size / 4 bytes, or nullptr.
  void* take(size_t size, size_t& block_size) {
    const std::lock_guard<std::mutex> lock(mutex_);
    size_t best = count_;
    for (size_t i = 0; i < count_; ++i)
      if (blocks_[i].size >= size && blocks_[i].size - size <= size / 4 &&
          (best == count_ || blocks_[i].size < blocks_[best].size))
        best = i;
    if (best == count_) return nullptr;
    const Block taken = blocks_[best];
    remove(best);
    RASTERCMP_UNPOISON(taken.start, taken.size);
    block_size = taken.size;
    return taken.start;
  }

  // Keeps the block, giving back the oldest ones it displaces; false (nothing kept) where the block
  // is below kCachedMinBytes or above kCacheBytes.
  bool keep(void* start, size_t size) {
    if (size < kCachedMinBytes || size > kCacheBytes) return false;
    Block evicted[kCacheBlocks];
    size_t evictions = 0;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      while (count_ == kCacheBlocks || bytes_ + size > kCacheBytes) {
        evicted[evictions++] = blocks_[0];
        remove(0);
      }
      RASTERCMP_POISON(start, size);
      blocks_[count_++] = Block{start, size};
      bytes_ += size;
    }
    give_back(evicted, evictions);
    return true;
  }

  size_t bytes() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return bytes_;
  }

  void release() {
    Block released[kCacheBlocks];
    size_t count = 0;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (count = 0; count_ > 0; ++count) {
        released[count] = blocks_[0];
        remove(0);
      }
    }
    give_back(released, count);
  }

  size_t count() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }

 private:
  struct Block {
    void* start;
    size_t size;
  };

  // Blocks taken out of the cache, to the system (outside the lock).
  static void give_back(const Block* blocks, size_t count) {
    for (size_t i = 0; i < count; ++i) {
      RASTERCMP_UNPOISON(blocks[i].start, blocks[i].size);
      std::free(blocks[i].start);
    }
  }

  void remove(size_t i) {  // keeps the others oldest first
    bytes_ -= blocks_[i].size;
    for (; i + 1 < count_; ++i) blocks_[i] = blocks_[i + 1];
    --count_;
  }

  std::mutex mutex_;
  Block blocks_[kCacheBlocks] = {};
  size_t count_ = 0, bytes_ = 0;
};

// Never destroyed: buffers in thread-local and static storage are freed during exit, after any
// static of this file would be gone.
BlockCache& block_cache() {
  static BlockCache* const cache = new BlockCache;
  return *cache;
}

}  // namespace

void* allocate_coloured(size_t bytes, uint32_t colour) {
  if (bytes > SIZE_MAX - kPage - kHalfPage) throw std::bad_alloc();
  const size_t size = bytes + kPage + kHalfPage;
  if (size >= kCachedMinBytes) {
    size_t kept_size = 0;
    if (void* kept = block_cache().take(size, kept_size)) return storage_of(kept, kept_size, colour);
  }
  void* start = std::malloc(size);
  if (start == nullptr) throw std::bad_alloc();
  return storage_of(start, size, colour);
}

void free_coloured(void* data) noexcept {
  if (data == nullptr) return;
  void* start = nullptr;
  size_t size = 0;
  std::memcpy(&start, static_cast<char*>(data) - sizeof(void*), sizeof(void*));
  std::memcpy(&size, static_cast<char*>(data) - 2 * sizeof(void*), sizeof(size));
  if (!block_cache().keep(start, size)) std::free(start);
}

size_t kept_block_bytes() { return block_cache().bytes(); }
size_t kept_block_count() { return block_cache().count(); }
void release_kept_blocks() { block_cache().release(); }

}  // namespace rastercmp
