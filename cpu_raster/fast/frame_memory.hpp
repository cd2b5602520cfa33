// Memory of a fast render (docs/performance.md, "How the fast path works"): the result buffers
// are sized without a separate clear pass (tiles are cleared by their workers), large fresh buffers
// ask for transparent huge pages (one fault per 2 MiB instead of 512), and the per-vertex arrays
// live in a per-thread scratch buffer that is kept between renders (its size: 24 bytes per
// position of the largest scene drawn so far on that thread).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "cpu_raster/fast/fast_vertices.hpp"
#include "model/pixel_buffer.hpp"

namespace rastercmp::cpu::fast {

// Gives `buffer` exactly `count` elements, reusing its memory when it is large enough; the
// contents are unspecified (the caller writes every element). New memory gets `colour`
// (model/pixel_buffer.hpp): the owner buffer 0, the depth buffer 1.
void size_buffer(PixelBuffer& buffer, size_t count, uint32_t colour);

// madvise(MADV_HUGEPAGE) over the 2 MiB-aligned part of [data, data + bytes), where supported.
void advise_huge_pages(void* data, size_t bytes);

class VertexScratch {
 public:
  FastVertex* acquire(size_t count);  // valid until the next acquire on this object

 private:
  std::unique_ptr<FastVertex[]> data_;
  size_t capacity_ = 0;
};

// The calling thread's scratch.
VertexScratch& thread_vertex_scratch();

// The calling thread's scratch of `count` 16-bit tile rows (contents unspecified), valid until the next call.
int16_t* thread_row_scratch(size_t count);

// The calling thread's scratch of `count` words (contents unspecified), one per use, each valid
// until that use's next call.
enum class WordScratch { BlockRows, ListReach };
uint32_t* thread_word_scratch(size_t count, WordScratch use);

}  // namespace rastercmp::cpu::fast
