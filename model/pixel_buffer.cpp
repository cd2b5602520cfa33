#include "model/pixel_buffer.hpp"

#include <cstdlib>
#include <cstring>
#include <new>

namespace rastercmp {
namespace {

constexpr uintptr_t kPage = 4096;
constexpr uintptr_t kHalfPage = kPage / 2;

}  // namespace

// The block: [start, start + bytes + kPage + kHalfPage); the storage begins at the first page
// boundary at least one pointer past `start`, plus the colour's half page, and the pointer just
// before it holds `start`.
void* allocate_coloured(size_t bytes, uint32_t colour) {
  if (bytes > SIZE_MAX - kPage - kHalfPage) throw std::bad_alloc();
  void* start = std::malloc(bytes + kPage + kHalfPage);
  if (start == nullptr) throw std::bad_alloc();
  const uintptr_t page = (reinterpret_cast<uintptr_t>(start) + sizeof(void*) + kPage - 1) & ~(kPage - 1);
  void* data = reinterpret_cast<void*>(page + (colour & 1u) * kHalfPage);
  std::memcpy(static_cast<char*>(data) - sizeof(void*), &start, sizeof(void*));
  return data;
}

void free_coloured(void* data) noexcept {
  if (data == nullptr) return;
  void* start = nullptr;
  std::memcpy(&start, static_cast<char*>(data) - sizeof(void*), sizeof(void*));
  std::free(start);
}

}  // namespace rastercmp
