// Which primitives make up a block of eight small triangles (small_triangles.hpp), shared by the
// workers' walk and the block-row phase (band_worker*.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <type_traits>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/fast/fast_frame.hpp"
#include "cpu_raster/fast/small_triangles.hpp"

namespace rastercmp::cpu::fast {

// The draw's vertex numbers of primitive i (assemble.hpp, provoking vertex first).
template <Topology T>
inline std::array<uint32_t, 3> vertex_numbers(uint32_t i) {
  if constexpr (T == Topology::TriangleList) return {3 * i, 3 * i + 1, 3 * i + 2};
  if constexpr (T == Topology::TriangleStrip)
    return (i & 1) == 0 ? std::array<uint32_t, 3>{i, i + 1, i + 2} : std::array<uint32_t, 3>{i, i + 2, i + 1};
  return {i + 1, i + 2, 0};  // fan
}

// f(topology, indexed) with the draw's triangle topology and whether it has an index buffer as
// std::integral_constant arguments, for code templated on them (vertex_numbers); otherwise() for
// any other topology. Both return the same type.
template <class F, class Otherwise>
decltype(auto) on_triangle_layout(const Draw& draw, F&& f, Otherwise&& otherwise) {
  using List = std::integral_constant<Topology, Topology::TriangleList>;
  using Strip = std::integral_constant<Topology, Topology::TriangleStrip>;
  using Fan = std::integral_constant<Topology, Topology::TriangleFan>;
  const bool indexed = !draw.indices.empty();
  switch (draw.topology) {
    case Topology::TriangleList: return indexed ? f(List{}, std::true_type{}) : f(List{}, std::false_type{});
    case Topology::TriangleStrip: return indexed ? f(Strip{}, std::true_type{}) : f(Strip{}, std::false_type{});
    case Topology::TriangleFan: return indexed ? f(Fan{}, std::true_type{}) : f(Fan{}, std::false_type{});
    default: return otherwise();
  }
}

// What every block of draw d shares: the vertex array, region, face and cull state, depth.
inline void fill_block_draw(const FastFrame& frame, uint32_t d, SmallBlock& slot) {
  const Draw& draw = frame.scene->draws[d];
  SmallBlockInput& in = slot.in;
  in.vertices = frame.draws[d].vertices;
  in.region = frame.exact.region;
  in.front_ccw = draw.state.front_face == FrontFace::CounterClockwise;
  in.cull = draw.state.cull_mode;
  in.depth = frame.draws[d].raster.kernel;
  in.window_ok = frame.draws[d].raster.window_block_fn != nullptr;
}

// Lane l's corners of block `block` of a draw of `count` primitives: through the index buffer for
// full blocks of indexed lists, else copied. The rest of slot.in comes from fill_block_draw.
template <Topology T, bool Indexed>
inline void fill_block_corners(const uint32_t* indices, uint32_t count, uint32_t block, SmallBlock& slot) {
  SmallBlockInput& in = slot.in;
  slot.first = block * 8;
  in.count = std::min(count - slot.first, 8u);
  if (T == Topology::TriangleList && Indexed && in.count == 8) {
    for (int k = 0; k < 3; ++k) in.corners[k] = indices + 3 * size_t(slot.first) + k;
    in.stride = 3;
  } else {
    for (uint32_t l = 0; l < 8; ++l) {
      const std::array<uint32_t, 3> n = vertex_numbers<T>(slot.first + (l < in.count ? l : 0));
      for (int k = 0; k < 3; ++k) in.corners_copy(k)[l] = Indexed ? indices[n[k]] : n[k];
    }
    for (int k = 0; k < 3; ++k) in.corners[k] = in.corners_copy(k);
    in.stride = 1;
  }
}

}  // namespace rastercmp::cpu::fast
