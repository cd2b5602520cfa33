// Memory of an attachment (RenderResult::owner and depth_raw, the CPU paths' RenderTargets): a
// std::vector whose storage starts `colour` * 2 KiB into a 4 KiB page.
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
#include <type_traits>
#include <vector>

namespace rastercmp {

// `bytes` of storage starting colour * 2 KiB (colour 0 or 1) into a 4 KiB page, 64-byte aligned;
// std::bad_alloc when none is left. Freed by free_coloured.
void* allocate_coloured(size_t bytes, uint32_t colour);
void free_coloured(void* data) noexcept;

template <class T>
class PixelAllocator {
 public:
  using value_type = T;
  // Every allocator frees every block (free_coloured finds the block's start itself), so moves and
  // swaps between buffers of different colours are plain pointer moves.
  using is_always_equal = std::true_type;
  using propagate_on_container_move_assignment = std::true_type;

  PixelAllocator() = default;
  explicit PixelAllocator(uint32_t colour) : colour_(colour) {}
  template <class U>
  PixelAllocator(const PixelAllocator<U>& other) : colour_(other.colour()) {}

  T* allocate(size_t n) { return static_cast<T*>(allocate_coloured(n * sizeof(T), colour_)); }
  void deallocate(T* p, size_t) noexcept { free_coloured(p); }
  uint32_t colour() const { return colour_; }

  template <class U>
  bool operator==(const PixelAllocator<U>&) const {
    return true;
  }

 private:
  uint32_t colour_ = 0;
};

using PixelBuffer = std::vector<uint32_t, PixelAllocator<uint32_t>>;

}  // namespace rastercmp
