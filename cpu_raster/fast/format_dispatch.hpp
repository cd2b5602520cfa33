// The fast path's dispatch over depth formats (docs/depth-formats.md): every kernel family is
// instantiated for each DepthFormat of the depth-format table's list (kAllDepthFormats,
// model/depth_format.hpp) and each CompareOp, at compile time, so a new format reaches every
// dispatch table from that one list. The kernels themselves read their format's facts
// (encoding, conversion, constants) from depth_format_info(F).
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "model/depth_format.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::fast {

inline constexpr size_t kCompareOpCount = size_t(CompareOp::Always) + 1;

namespace format_dispatch_detail {

template <class Maker, DepthFormat F, size_t... I>
constexpr auto op_row(std::index_sequence<I...>) {
  return std::array{Maker::template get<F, CompareOp(I)>()...};
}

template <class Maker, size_t... K>
constexpr auto format_rows(std::index_sequence<K...>) {
  return std::array{op_row<Maker, kAllDepthFormats[K]>(std::make_index_sequence<kCompareOpCount>{})...};
}

template <class Body, size_t... K>
[[gnu::always_inline]] inline void visit(DepthFormat format, Body& body, std::index_sequence<K...>) {
  (void)((format == kAllDepthFormats[K] ? (body.template operator()<kAllDepthFormats[K]>(), true) : false) || ...);
}

}  // namespace format_dispatch_detail

// table[format][op] = Maker::get<format, op>() for every DepthFormat (index = enum value) and every
// CompareOp: one kernel family's dispatch table, built at compile time.
template <class Maker>
constexpr auto kernel_table() {
  return format_dispatch_detail::format_rows<Maker>(std::make_index_sequence<kAllDepthFormats.size()>{});
}

// The entry for (format, op); without depth (None) the op is Always.
template <class Table>
constexpr auto select_kernel(const Table& table, DepthFormat format, CompareOp op) {
  return table[size_t(format)][format == DepthFormat::None ? size_t(CompareOp::Always) : size_t(op)];
}

// Calls body.template operator()<F>() with F the compile-time twin of `format`. Always inlined, so
// a lambda body carrying the caller's target attribute inlines into the caller.
template <class Body>
[[gnu::always_inline]] inline void with_depth_format(DepthFormat format, Body&& body) {
  format_dispatch_detail::visit(format, body, std::make_index_sequence<kAllDepthFormats.size()>{});
}

}  // namespace rastercmp::cpu::fast
