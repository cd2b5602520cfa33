// format_explanation (cpu_raster/explain.hpp): the records as a fixed-width table.
#include <string>

#include <fmt/core.h>

#include "cpu_raster/exact/explain.hpp"

namespace rastercmp {
namespace {

const char* cull_text(CullReason reason) {
  switch (reason) {
    case CullReason::None: return "set up";
    case CullReason::Facing: return "culled: facing";
    case CullReason::Degenerate: return "culled: degenerate";
    case CullReason::FloatCull: return "culled: float cull";
    case CullReason::OutsideRegion: return "outside region";
    case CullReason::NonFinite: return "non-finite";
  }
  return "?";
}

std::string clip_text(const FragmentRecord& r) {
  if (!r.clipped) return "-";
  return fmt::format("{}/{}", r.clip_piece + 1, r.clip_pieces);
}

std::string edges_text(const FragmentRecord& r) {
  std::string text;
  for (uint32_t i = 0; i < r.edge_count; ++i)
    text += fmt::format("{}{}{}", i ? " " : "", r.edge_value[i], r.edge_inclusive[i] ? "*" : "");
  for (uint32_t i = 0; i < r.scissor_plane_count; ++i) text += fmt::format(" s{}", r.scissor_value[i]);
  return text;
}

std::string coverage_text(const FragmentRecord& r) {
  switch (r.miss) {
    case MissReason::None: return "yes";
    case MissReason::Edge: return fmt::format("no: edge {}", r.failing_plane);
    case MissReason::Scissor: return fmt::format("no: scissor {}", r.failing_plane - int(r.edge_count));
    case MissReason::NotVisited: return "no: not visited";
  }
  return "?";
}

std::string depth_columns(const FragmentRecord& r) {
  if (!r.depth_tested)
    return fmt::format("{:>13} {:>13} {:>13} {:>10} {:>8} {:>10} {:>4} {:>10}", "-", "-", "-", "-", "-", "-", "-", "-");
  return fmt::format("{:>13.9g} {:>13.9g} {:>13.9g} {:>#10x} {:>8} {:>#10x} {:>4} {:>#10x}", r.depth_interpolated,
                     r.bias_offset, r.depth_clamped, r.depth_raw, to_string(r.compare_op), r.stored_before,
                     r.depth_passed ? "pass" : "fail", r.stored_after);
}

std::string detail_lines(const FragmentRecord& r) {
  std::string text;
  if (r.float_cull_ran) text += fmt::format("      float cull det {:.9g}\n", r.float_det);
  if (r.depth_tested && r.bias_computed)
    text += fmt::format("      bias: m {:.9g}, r {:.9g}, constant {:.9g}, slope {:.9g}, clamp {:.9g}{} -> o {:.9g}\n",
                        r.bias_m, r.bias_r, r.bias_constant_factor, r.bias_slope_factor, r.bias_clamp,
                        r.bias_clamp_applied ? " (applied)" : "", r.bias_offset);
  if (r.one_fragment_per_pixel)
    text += "      one fragment for the pixel: depth tested and written at sample 0, owner written to every sample\n";
  if (r.depth_tested)
    text += fmt::format("      z {:.9g} + o = {:.9g}, [0,1] {:.9g}, depth clamp {} {:.9g}\n", r.depth_interpolated,
                        r.depth_with_offset, r.depth_clamped_01, r.depth_clamp_enabled ? "on" : "off", r.depth_clamped);
  return text;
}

}  // namespace

std::string format_explanation(const std::vector<FragmentRecord>& records) {
  if (records.empty()) return "no primitive reached this pixel\n";
  std::string text = fmt::format(
      "{:>4} {:>6} {:>8} {:>5} {:<18} {:<40} {:<15} {:>13} {:>13} {:>13} {:>10} {:>8} {:>10} {:>4} {:>10} {}\n", "draw",
      "prim", "kind", "clip", "set-up", "E (* top-left +1, s scissor)", "covered", "z", "o", "z final", "raw", "op",
      "before", "test", "after", "owner");
  for (const FragmentRecord& r : records) {
    text += fmt::format("{:>4} {:>6} {:>8} {:>5} {:<18} {:<40} {:<15} {} {}\n", r.draw_index, r.primitive_index,
                        r.is_line ? "line" : "triangle", clip_text(r), cull_text(r.cull), edges_text(r),
                        r.cull == CullReason::None ? coverage_text(r) : "-", depth_columns(r),
                        r.owner_written ? "written" : "-");
    text += detail_lines(r);
  }
  return text;
}

}  // namespace rastercmp
