// Memory of a fast render (docs/performance.md, "How the fast path works"): the result buffers
// are sized without a separate clear pass (tiles are cleared by their workers), large fresh buffers
// ask for transparent huge pages (one fault per 2 MiB instead of 512), and the per-vertex arrays
// live in a per-thread scratch buffer that is kept between renders (its size: 24 bytes per
// position of the largest scene drawn so far on that thread).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "cpu_raster/fast/fast_vertices.hpp"
#include "model/pixel_buffer.hpp"

namespace rastercmp::cpu::fast {

// Gives `buffer` exactly `count` elements, reusing its memory when it is large enough; the
// contents are unspecified (the caller writes every element). New memory gets `colour`
// (model/pixel_buffer.hpp): the owner buffer 0, the depth buffer 1; and is not zeroed first
// (PixelFill::Unwritten): the render's own writes are the first, each value cleared, drawn or
// packed by a worker.
void size_buffer(PixelBuffer& buffer, size_t count, uint32_t colour);

// madvise(MADV_HUGEPAGE) over the 2 MiB-aligned part of [data, data + bytes), where supported.
void advise_huge_pages(void* data, size_t bytes);

// Storage of the vertex phase's output, starting on a 64-byte line: the AVX-512 pass stores sixteen
// vertices as four 64-byte vectors, the AVX2 pass eight as four of 32 bytes, each then within one
// line (from malloc, which puts a large block 16 bytes into its pages, every 64-byte store crossed
// two lines).
class VertexScratch {
 public:
  static constexpr size_t kAlignment = 64;
  FastVertex* acquire(size_t count);  // valid until the next acquire on this object

 private:
  struct Free {
    void operator()(FastVertex* p) const { ::operator delete[](p, std::align_val_t{kAlignment}); }
  };
  std::unique_ptr<FastVertex[], Free> data_;
  size_t capacity_ = 0;
};

// The calling thread's scratch.
VertexScratch& thread_vertex_scratch();

// The row pitch, in pixels, of a frame of one sample per pixel while the fast path draws it: its
// width, or one 64-byte line more a row where rows of that width would fall in one or two sets of
// the L1 data cache. That happens to a row of a multiple of 2 KiB (a width of 512, 1024, ...
// pixels) on hosts whose L1 has 4 KiB a way (this host's: 48 KiB of 12 ways, 64 sets;
// /sys/devices/system/cpu/cpu0/cache/index0): then the rows a steep line covers in one column
// share a set, and their loads and stores wait on one another (`rastercmp_bench_access`: the steps
// of 40-row lines 1.5-8 times slower at a pitch of 1,024 pixels than at 1,040, by kind of access;
// docs/performance.md, "Lines and multisampled frames"). With the wider pitch consecutive rows
// lie one set apart. The pitch changes where values live, never a value: the frame's pixels are
// copied to the result at its width when it is drawn (BandWorker::pack_tile_row).
inline constexpr size_t kL1WayBytes = 4096;
// Whether gcd(row_bytes, kL1WayBytes) >= kL1WayBytes / 2: with the way a power of two, whether
// row_bytes is a multiple of half a way.
static_assert(std::has_single_bit(kL1WayBytes));
inline bool rows_share_l1_sets(size_t row_bytes) { return row_bytes % (kL1WayBytes / 2) == 0; }
inline uint32_t spread_row_pitch(uint32_t width) {
  constexpr uint32_t kLinePixels = 64 / sizeof(uint32_t);
  return rows_share_l1_sets(size_t(width) * sizeof(uint32_t)) ? width + kLinePixels : width;
}

// The calling thread's attachments of a frame drawn at a wider pitch than its width (kept between
// renders: render_fast_into moves them into the frame's targets and back). A frame is drawn so
// only while both fit in kMaxPitchedBytes, which bounds what a thread keeps.
inline constexpr size_t kMaxPitchedBytes = size_t(64) << 20;
struct PitchedAttachments {
  PixelBuffer owner, depth;
};
PitchedAttachments& thread_pitched_attachments();

// The calling thread's scratch of `count` 16-bit tile rows (contents unspecified), valid until the next call.
int16_t* thread_row_scratch(size_t count);

// The calling thread's scratch of `count` words (contents unspecified), one per use, each valid
// until that use's next call.
enum class WordScratch { BlockRows, ListReach };
uint32_t* thread_word_scratch(size_t count, WordScratch use);

}  // namespace rastercmp::cpu::fast
