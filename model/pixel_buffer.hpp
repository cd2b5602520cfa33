// Memory of an attachment (RenderResult::owner and depth_raw, the CPU paths' RenderTargets): a
// std::vector whose storage starts `colour` * 2 KiB into a 4 KiB page, and whose growth (resize(n),
// PixelBuffer(n)) zeroes the new elements as std::vector's does, or, for an allocator made with
// PixelFill::Unwritten, leaves them as the memory holds them: the fast path's attachments, every element
// of which it writes before reading (its tiles cleared or drawn), so that a render into new
// buffers does not write them twice (perspective into new buffers at two threads 0.96-1.02 ms
// instead of 1.17-1.39; docs/performance-log.md, "Result buffers not zeroed before the render").
//
// Why: with a row pitch that is a multiple of 4 KiB (a width that is a multiple of 1024 pixels)
// every row of a 16-pixel column band falls in the same L1 set (Zen 5: 64 sets of 12 ways), and
// glibc starts every large block at the same offset in its page, so the owner and depth rows of
// a band shared those sets too. The fast path gives the depth buffer the other half of the page:
// at 1024x1024 and 2 threads perspective took 6.5% less time and fill_b2f 0.52 ms instead of 0.80
// (docs/performance-log.md, 17ad48f). The colour changes no value, only where the bytes live.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace rastercmp {

// `bytes` of storage starting colour * 2 KiB (colour 0 or 1) into a 4 KiB page, 64-byte aligned;
// std::bad_alloc when none is left. Freed by free_coloured. Its bytes are unspecified: a freed
// block of kCachedMinBytes or more is kept for the next request of its size or up to a fifth
// less (pixel_buffer.cpp), at most kCacheBlocks of them and kCacheBytes in all, the oldest given
// back to the system first.
void* allocate_coloured(size_t bytes, uint32_t colour);
void free_coloured(void* data) noexcept;

inline constexpr size_t kCachedMinBytes = size_t(256) << 10;
inline constexpr size_t kCacheBlocks = 8;
inline constexpr size_t kCacheBytes = size_t(128) << 20;

// The blocks kept, their bytes (each a whole block: storage and the page and a half around it).
size_t kept_block_bytes();
size_t kept_block_count();
// Gives every kept block back to the system (what a measure of a render's own memory starts from).
void release_kept_blocks();

// How a PixelBuffer's growth forms its new elements (PixelAllocator::construct).
enum class PixelFill { Zero, Unwritten };

template <class T>
class PixelAllocator {
 public:
  using value_type = T;
  // Every allocator frees every block (free_coloured finds the block's start itself), so moves and
  // swaps between buffers of different colours are plain pointer moves.
  using is_always_equal = std::true_type;
  using propagate_on_container_move_assignment = std::true_type;

  PixelAllocator() = default;
  explicit PixelAllocator(uint32_t colour, PixelFill fill = PixelFill::Zero)
      : colour_(colour), zero_(fill == PixelFill::Zero) {}
  template <class U>
  PixelAllocator(const PixelAllocator<U>& other) : colour_(other.colour()), zero_(other.fill() == PixelFill::Zero) {}

  T* allocate(size_t n) { return static_cast<T*>(allocate_coloured(n * sizeof(T), colour_)); }
  void deallocate(T* p, size_t) noexcept { free_coloured(p); }
  uint32_t colour() const { return colour_; }
  PixelFill fill() const { return zero_ ? PixelFill::Zero : PixelFill::Unwritten; }

  // An element added without a value: value-initialized (zero), or default-initialized.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    if (zero_)
      ::new (static_cast<void*>(p)) U();
    else
      ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  // A copy of a buffer zeroes its growth whatever the original does: only the buffers the fast
  // path sizes for itself leave it unwritten.
  PixelAllocator select_on_container_copy_construction() const { return PixelAllocator(colour_); }

  template <class U>
  bool operator==(const PixelAllocator<U>&) const {
    return true;
  }

 private:
  uint32_t colour_ = 0;
  bool zero_ = true;  // a bool, which no element store may alias: the test stays out of resize's loop
};

using PixelBuffer = std::vector<uint32_t, PixelAllocator<uint32_t>>;

}  // namespace rastercmp
