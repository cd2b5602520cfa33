#include "cpu_raster/classic/classic_explain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "cpu_raster/classic/classic_fragments.hpp"
#include "cpu_raster/classic/classic_visibility.hpp"
#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/explain.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "cpu_raster/exact/render_exact.hpp"
#include "cpu_raster/methods/line_bresenham.hpp"
#include "cpu_raster/methods/line_dda.hpp"
#include "model/errors.hpp"
#include "model/render_result.hpp"

namespace rastercmp {
namespace {

using namespace cpu::classic;

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", v + 0.0);  // + 0.0: no "-0"
  return buffer;
}

// All the digits of a double, where the last bits are the point (DDA's accumulated error).
std::string num17(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string hex(uint32_t v) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%#x", v);
  return buffer;
}

std::string vec3_text(const methods::Vec3& v) { return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")"; }

std::string ordinal(size_t n) {
  const size_t tens = n % 100;
  const char* suffix = tens >= 11 && tens <= 13 ? "th"
                       : n % 10 == 1            ? "st"
                       : n % 10 == 2            ? "nd"
                       : n % 10 == 3            ? "rd"
                                                : "th";
  return std::to_string(n) + suffix;
}

std::string methods_line(const CpuOptions& options) {
  std::string text;
  for (const MethodChoice& c : options.methods) text += " " + c.stage + "=" + c.name;
  return text;
}

std::string choice_of(const CpuOptions& options, const std::string& stage, const std::string& fallback) {
  for (const MethodChoice& c : options.methods)
    if (c.stage == stage) return c.name;
  return fallback;
}

std::string owner_words(uint32_t owner) {
  return owner == kOwnerBackground
             ? std::string("background")
             : "draw " + std::to_string(owner_draw(owner)) + " primitive " + std::to_string(owner_primitive(owner));
}

std::string primitive_name(size_t index, const ClassicPrimitive& p) {
  return "#" + std::to_string(index) + " draw " + std::to_string(p.draw_index) + " primitive " +
         std::to_string(p.primitive_index);
}

std::string primitive_line(size_t index, const ClassicPrimitive& p) {
  std::string text = "  " + primitive_name(index, p) + (p.is_line ? " line" : " triangle");
  if (p.clipped || p.pieces > 1)
    text += " (clip piece " + std::to_string(p.piece + 1) + "/" + std::to_string(p.pieces) + ")";
  text += ", window";
  const size_t n = p.is_line ? 2 : 3;
  for (size_t k = 0; k < n; ++k)
    text += " (" + num(p.window[k].x) + ", " + num(p.window[k].y) + ", z " + num(p.window[k].z) + ", w " +
            num(p.w_clip[k]) + ")";
  return text + "\n";
}

// --- the clip stage's variables ---

const char* plane_name(methods::ClipPlane plane) {
  switch (plane) {
    case methods::ClipPlane::XLow: return "x >= -w";
    case methods::ClipPlane::XHigh: return "x <= w";
    case methods::ClipPlane::YLow: return "y >= -w";
    case methods::ClipPlane::YHigh: return "y <= w";
    case methods::ClipPlane::ZLow: return "z >= 0";
    case methods::ClipPlane::ZHigh: return "z <= w";
  }
  return "?";
}

const char* side_name(methods::RectSide side) {
  switch (side) {
    case methods::RectSide::XMin: return "x = x_min";
    case methods::RectSide::XMax: return "x = x_max";
    case methods::RectSide::YMin: return "y = y_min";
    case methods::RectSide::YMax: return "y = y_max";
  }
  return "?";
}

std::string code_hex(uint8_t code) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "0x%02x", unsigned(code));
  return buffer;
}

std::string line_clip_text(const ClassicPrimitive& p, const std::string& clip) {
  const LineClipTrace& t = p.line_clip;
  std::string text = "    clip=" + clip + ": clip-space outcodes p0 " + code_hex(t.code_p0) + ", p1 " +
                     code_hex(t.code_p1) + " (1 x < -w, 2 x > w, 4 y < -w, 8 y > w, 16 z < 0, 32 z > w)";
  if (t.trivial) return text + ": OR 0, trivially accepted, not clipped\n";
  text += ", OR " + code_hex(uint8_t(t.code_p0 | t.code_p1)) + ", AND " + code_hex(uint8_t(t.code_p0 & t.code_p1));
  text += "\n";
  for (const LiangBarskyPlane& row : t.liang_barsky) {
    text += std::string("      ") + plane_name(row.plane) + ": d0 " + num(row.d0) + ", d1 " + num(row.d1);
    if (row.entering)
      text += ", entering at t = d0 / (d0 - d1) = " + num(row.t) + " (raises t_in)";
    else if (row.leaving)
      text += ", leaving at t = d0 / (d0 - d1) = " + num(row.t) + " (lowers t_out)";
    else
      text += ", both ends inside";
    text += "\n";
  }
  if (!t.liang_barsky.empty())
    text += "      -> t_in " + num(t.t_in) + ", t_out " + num(t.t_out) +
            " (t_in <= t_out: the part from t_in to t_out is kept)\n";
  for (size_t k = 0; k < t.passes_3d.size(); ++k) {
    const methods::CohenSutherland3dPass& pass = t.passes_3d[k];
    text +=
        "      pass " + std::to_string(k + 1) + ": outcodes " + code_hex(pass.code_p0) + " / " + code_hex(pass.code_p1);
    text += pass.clipped
                ? std::string(", p") + (pass.clipped_p0 ? "0" : "1") + " cut at " + plane_name(pass.plane)
                : std::string((pass.code_p0 | pass.code_p1) == 0 ? ": OR 0, accepted" : ": AND != 0, rejected");
    text += "\n";
  }
  if (!t.passes_2d.empty())
    text += "      window-space segment against the viewport [" + num(t.window.x_min) + ", " + num(t.window.x_max) +
            "] x [" + num(t.window.y_min) + ", " + num(t.window.y_max) +
            "], 4-bit outcodes (1 x < x_min, 2 x > x_max, 4 y < y_min, 8 y > y_max)\n";
  for (size_t k = 0; k < t.passes_2d.size(); ++k) {
    const methods::CohenSutherlandPass& pass = t.passes_2d[k];
    text +=
        "      pass " + std::to_string(k + 1) + ": outcodes " + code_hex(pass.code_p0) + " / " + code_hex(pass.code_p1);
    text += pass.clipped
                ? std::string(", p") + (pass.clipped_p0 ? "0" : "1") + " cut at " + side_name(pass.side)
                : std::string((pass.code_p0 | pass.code_p1) == 0 ? ": OR 0, accepted" : ": AND != 0, rejected");
    text += "\n";
  }
  if (!t.cyrus_beck.empty()) {
    text += "      window-space segment against the viewport [" + num(t.window.x_min) + ", " + num(t.window.x_max) +
            "] x [" + num(t.window.y_min) + ", " + num(t.window.y_max) + "] as a convex polygon\n";
    for (const methods::CyrusBeckStep& step : t.cyrus_beck) {
      text += "      edge " + std::to_string(step.edge) + ": ";
      text += step.crossing == methods::CyrusBeckCrossing::Parallel
                  ? std::string("parallel")
                  : std::string(step.crossing == methods::CyrusBeckCrossing::Entering ? "entering" : "leaving") +
                        " at t " + num(step.t_hit);
      text += " -> t_in " + num(step.t_in) + ", t_out " + num(step.t_out) + "\n";
    }
    text += "      -> t_in " + num(t.t_in) + ", t_out " + num(t.t_out) + "\n";
  }
  return text;
}

std::string triangle_clip_text(const ClassicPrimitive& p, const std::string& clip) {
  const uint8_t any = uint8_t(p.vertex_codes[0] | p.vertex_codes[1] | p.vertex_codes[2]);
  std::string text = "    clip=" + clip + ": vertex outcodes " + code_hex(p.vertex_codes[0]) + " " +
                     code_hex(p.vertex_codes[1]) + " " + code_hex(p.vertex_codes[2]) +
                     " (1 x < -w, 2 x > w, 4 y < -w, 8 y > w, 16 z < 0, 32 z > w), OR " + code_hex(any);
  if (any == 0) return text + ": inside, not clipped\n";
  return text + ": clipped into a polygon of " + std::to_string(p.pieces + 2) + " vertices, fanned into " +
         std::to_string(p.pieces) + " triangle(s); this is piece " + std::to_string(p.piece + 1) + "\n";
}

// --- coverage ---

// The runs of x of a row's fragments: "[x0, x1) [x2, x3)".
std::string row_spans(const std::vector<Fragment>& fragments, int32_t y) {
  std::string text;
  bool open = false;
  int32_t begin = 0, last = 0;
  const auto close = [&] {
    if (open) text += " [" + std::to_string(begin) + ", " + std::to_string(last + 1) + ")";
  };
  for (const Fragment& f : fragments) {
    if (f.y != y) continue;
    if (open && f.x == last + 1) {
      last = f.x;
      continue;
    }
    close();
    open = true, begin = last = f.x;
  }
  close();
  return text.empty() ? " none" : text;
}

// Whether the primitive's window extent comes near the pixel.
bool window_extent_near(const cpu::WindowVertex* v, size_t n, int32_t x, int32_t y) {
  double x0 = v[0].x, x1 = x0, y0 = v[0].y, y1 = y0;
  for (size_t k = 1; k < n; ++k) {
    x0 = std::fmin(x0, v[k].x), x1 = std::fmax(x1, v[k].x);
    y0 = std::fmin(y0, v[k].y), y1 = std::fmax(y1, v[k].y);
  }
  return x + 1 >= x0 && x <= x1 && y + 1 >= y0 && y <= y1;
}

bool primitive_near(const ClassicPrimitive& p, int32_t x, int32_t y) {
  return window_extent_near(p.window.data(), p.is_line ? 2 : 3, x, y);
}

struct PixelState {
  int32_t x = 0, y = 0;
  uint32_t sample = 0;
  uint32_t stored = 0;
  uint32_t owner = kOwnerBackground;
};

std::string depth_test_text(const ClassicPrimitive& p, uint32_t raw, bool test, PixelState& pixel, bool& passed) {
  passed = true;
  if (!p.depth.active) return "no depth test";
  std::string text = "raw " + hex(raw) + " = " + num(depth_raw_to_value(p.depth.format, raw));
  if (test) {
    passed = cpu::depth_test_passes(p.depth.op, p.depth.format, raw, pixel.stored);
    text += "; test " + std::string(to_string(p.depth.op)) + " against stored " + hex(pixel.stored) + ": " +
            (passed ? "pass" : "fail");
  } else {
    text += "; painted without a depth test";
  }
  if (passed && p.depth.write) pixel.stored = raw;
  return text + ", stored after " + hex(pixel.stored);
}

// The exact rule on this primitive at the pixel: the set-up's 24.8 planes (top-left rule) and,
// when covered, the plane depth.
cpu::SampleVerdict exact_verdict(const ClassicPrimitive& p, const ClassicMethods& chosen, const PixelState& pixel) {
  cpu::DepthTestState depth = p.depth;
  if (chosen.depth == DepthMethod::NoFma) depth.fma = false;
  const uint32_t tested = p.raster.per_sample ? pixel.sample : 0;
  return cpu::evaluate_sample(p.raster, depth, pixel.x, pixel.y, tested, pixel.stored);
}

std::string edge_values(const ClassicPrimitive& p, const cpu::SampleVerdict& verdict) {
  std::string text = "E";
  for (uint32_t i = 0; i < p.raster.planes.count; ++i) {
    text += ' ';
    text += std::to_string(cpu::edge_value(p.raster.planes.plane[i], verdict.point.x_fixed, verdict.point.y_fixed));
  }
  return text;
}

std::string exact_coverage_words(const ClassicPrimitive& p, const cpu::SampleVerdict& verdict,
                                 const PixelState& pixel) {
  if (verdict.covered() && p.raster.visit.contains(pixel.x, pixel.y)) return "covered";
  if (!verdict.covered()) return "not covered (plane " + std::to_string(verdict.failing_plane) + " fails)";
  return "not covered (the rasterizer does not visit the pixel)";
}

// The exact rasterizer's history (fill and line exact, depth exact or no_fma, zbuffer).
std::string exact_history(const ClassicPrimitive& p, const ClassicMethods& chosen, PixelState& pixel) {
  const cpu::SampleVerdict verdict = exact_verdict(p, chosen, pixel);
  const uint32_t tested = p.raster.per_sample ? pixel.sample : 0;
  std::string text = "    coverage (24.8 edge planes, top-left rule) at sample " + std::to_string(tested) + ": " +
                     edge_values(p, verdict) + " -> " + exact_coverage_words(p, verdict, pixel) + "\n";
  const bool covered = verdict.covered() && p.raster.visit.contains(pixel.x, pixel.y);
  if (!covered) return text;
  bool passed = true;
  text += "    depth (" + std::string(chosen.depth == DepthMethod::NoFma ? "no_fma" : "exact") + " plane): z " +
          num(verdict.depth.interpolated) + ", " + depth_test_text(p, verdict.depth.raw, true, pixel, passed) + "\n";
  if (passed) pixel.owner = p.raster.owner;
  return text + "    owner " + (passed ? "written" : "kept") + "\n";
}

// line=dda at the pixel's column (x-major) or row (y-major): the accumulated minor coordinate and
// its rounding.
std::string dda_text(const ClassicPrimitive& p, const PixelState& pixel) {
  const auto [p0, p1] = line_method_endpoints(p);
  const methods::DdaTrace trace = methods::line_dda_trace(p0, p1);
  const char* major = trace.steep ? "y" : "x";
  const char* minor = trace.steep ? "x" : "y";
  std::string text = "      DDA steps along " + std::string(major) + " (" + (trace.major_step > 0 ? "+1" : "-1") +
                     " per step), " + minor + " += " + num17(trace.slope) + " per step, plotted at round(" + minor +
                     ") = floor(" + minor + " + 0.5)";
  const int32_t here = trace.steep ? pixel.y : pixel.x;
  for (size_t k = 0; k < trace.steps.size(); ++k) {
    const methods::DdaStep& step = trace.steps[k];
    if ((trace.steep ? step.pixel.y : step.pixel.x) != here) continue;
    const double start = trace.steep ? p0.x : p0.y;
    text += "\n      at " + std::string(major) + " = " + std::to_string(here) + " (step " + std::to_string(k) +
            "): " + minor + " = " + num17(step.minor) + " (accumulated; " + num(start) + " + " + std::to_string(k) +
            " x slope = " + num17(start + double(k) * trace.slope) + "), floor(" + num17(step.minor + 0.5) +
            ") = " + std::to_string(trace.steep ? step.pixel.x : step.pixel.y);
    return text + "\n";
  }
  return text + "\n      the line does not reach " + major + " = " + std::to_string(here) + "\n";
}

// line=bresenham at the pixel's column (or row, steep): the error term and the step decision.
std::string bresenham_text(const ClassicPrimitive& p, const PixelState& pixel) {
  const auto [p0, p1] = line_method_endpoints(p);
  const methods::BresenhamTrace trace = methods::line_bresenham_trace(p0, p1);
  std::string text = std::string("      Bresenham") + (trace.steep ? ", steep: x and y swapped" : "") +
                     (trace.swapped ? ", endpoints swapped (drawn p1 -> p0)" : "") + "; deltax " +
                     std::to_string(trace.delta_x) + ", deltay " + std::to_string(trace.delta_y) + ", ystep " +
                     std::to_string(trace.y_step) +
                     "; per step error += deltay, and 2 error >= deltax steps the minor axis (error -= deltax)";
  const int32_t here = trace.steep ? pixel.y : pixel.x;
  const char* major = trace.steep ? "y" : "x";
  for (size_t k = 0; k < trace.steps.size(); ++k) {
    const methods::BresenhamStep& step = trace.steps[k];
    if ((trace.steep ? step.pixel.y : step.pixel.x) != here) continue;
    const int64_t before = step.error_added - trace.delta_y;
    text += "\n      at " + std::string(major) + " = " + std::to_string(here) + " (step " + std::to_string(k) +
            "): plotted " + (trace.steep ? "x " : "y ") + std::to_string(trace.steep ? step.pixel.x : step.pixel.y) +
            " with error " + std::to_string(before) + "; error + deltay = " + std::to_string(step.error_added) +
            ", 2 error = " + std::to_string(2 * step.error_added) + (step.minor_step ? " >= " : " < ") + "deltax " +
            std::to_string(trace.delta_x) + (step.minor_step ? ": the minor axis steps, error " : ": no step, error ") +
            std::to_string(step.error_after);
    return text + "\n";
  }
  return text + "\n      the line does not reach " + major + " = " + std::to_string(here) + "\n";
}

std::string coverage_text(const ClassicPrimitive& p, const ClassicMethods& chosen, const std::string& fill,
                          const std::string& line, const cpu::PixelRect& region, const PixelState& pixel,
                          const std::vector<Fragment>& fragments, std::optional<size_t> at) {
  const cpu::SampleVerdict exact = exact_verdict(p, chosen, pixel);
  const std::string exact_line =
      "    exact: " + std::string(p.is_line ? "lavapipe's line planes" : "24.8 edge planes, top-left rule") + ", " +
      edge_values(p, exact) + " -> " + exact_coverage_words(p, exact, pixel) + "\n";
  if (p.is_line) {
    std::string text = "    line=" + line + ": ";
    if (chosen.line == LineMethod::Exact)
      return text + "row " + std::to_string(pixel.y) + " pixels" + row_spans(fragments, pixel.y) +
             (at ? " -> covered\n" : " -> not covered\n");
    const auto [p0, p1] = line_method_endpoints(p);
    text += "pixels from (" + std::to_string(p0.x) + ", " + std::to_string(p0.y) + ") to (" + std::to_string(p1.x) +
            ", " + std::to_string(p1.y) + "), " + std::to_string(fragments.size()) + " in the region";
    text += at ? ", this pixel is step " + std::to_string(*at) + " -> covered\n" : "; not this pixel\n";
    text += chosen.line == LineMethod::Dda ? dda_text(p, pixel) : bresenham_text(p, pixel);
    return text + exact_line;
  }
  std::string text = "    fill=" + fill + ": row " + std::to_string(pixel.y) + " spans" + row_spans(fragments, pixel.y);
  if (chosen.fill == FillMethod::Flood) {
    const FloodTrace trace = flood_trace(p, region);
    const methods::PixelXY cell{pixel.x - trace.origin.x, pixel.y - trace.origin.y};
    text += "; outline and flood grid at (" + std::to_string(trace.origin.x) + ", " + std::to_string(trace.origin.y) +
            ") " + std::to_string(trace.grid.width) + "x" + std::to_string(trace.grid.height) + ", seed ";
    text += trace.seed ? "(" + std::to_string(trace.seed->x) + ", " + std::to_string(trace.seed->y) + ")" : "none";
    text += ", " + std::to_string(trace.filled) + " cells filled; this pixel: ";
    if (!trace.grid.contains(cell))
      text += "outside the grid";
    else
      text += trace.grid.at(cell) == kFloodOutline  ? "on the Bresenham outline"
              : trace.grid.at(cell) == kFloodFilled ? "reached by the flood"
                                                    : "not reached (empty)";
  }
  text += at ? " -> covered\n" : " -> not covered\n";
  return chosen.fill == FillMethod::Exact ? text : text + exact_line;
}

std::string depth_method_text(const ClassicPrimitive& p, const ClassicMethods& chosen, const std::string& depth,
                              const PixelState& pixel) {
  std::string text;
  if (chosen.depth == DepthMethod::PseudoDepth) {
    text = "depth=" + depth + ": (1 - pz) / 2 = " + num(pseudo_depth_value(p, chosen.pseudo_far, pixel.x, pixel.y)) +
           " (near 25, far " + num(chosen.pseudo_far) + "), ";
  } else if (p.is_line && chosen.depth != DepthMethod::NoFma) {
    return "depth=" + depth + " (lines take the plane): ";
  } else if (chosen.depth == DepthMethod::PerspectiveCorrect) {
    const PerspectiveTrace t = perspective_trace(p, pixel.x, pixel.y);
    text = "depth=" + depth + ": at the pixel centre lambda (" + num(t.lambda[0]) + ", " + num(t.lambda[1]) + ", " +
           num(t.lambda[2]) + "), 1/w of the vertices (" + num(t.inv_w[0]) + ", " + num(t.inv_w[1]) + ", " +
           num(t.inv_w[2]) + "), 1/w at the sample = sum lambda/w = " + num(t.inv_w_at) +
           "; z = (sum lambda z/w) / (sum lambda/w) = " + num(t.z_perspective) +
           " (linear sum lambda z = " + num(t.z_linear) + "), ";
  } else {
    text = "depth=" + depth + ": ";
  }
  if (!p.depth.active || chosen.depth == DepthMethod::Exact) return text;
  // Beside the method's value: the exact plane's at the same pixel (lavapipe's evaluation, §3.2-§3.3).
  ClassicMethods plane = chosen;
  plane.depth = DepthMethod::Exact;
  const cpu::SampleVerdict exact = exact_verdict(p, plane, pixel);
  return text + "exact plane z " + num(exact.depth.interpolated) + " raw " +
         hex(fragment_depth_raw(p, plane, pixel.x, pixel.y)) + "; method ";
}

// cull=normal_dot_view: the triangles it removed near the pixel, each with N·V and, beside it,
// the exact path's snapped signed area there (its record at this pixel).
std::string culled_text(const ClassicFrame& prepared, const std::vector<FragmentRecord>& exact,
                        const PixelState& pixel) {
  std::string text;
  for (const CulledTriangle& c : prepared.culled) {
    std::vector<const FragmentRecord*> records;
    for (const FragmentRecord& r : exact)
      if (r.draw_index == c.draw_index && r.primitive_index == c.primitive_index) records.push_back(&r);
    const bool in_front = c.pos_clip[0].w > 0 && c.pos_clip[1].w > 0 && c.pos_clip[2].w > 0;
    if (records.empty() && !(in_front && window_extent_near(c.window.data(), 3, pixel.x, pixel.y))) continue;
    text += "    draw " + std::to_string(c.draw_index) + " primitive " + std::to_string(c.primitive_index) + ": N " +
            vec3_text(c.test.normal) + ", V " + vec3_text(c.test.view) + ", N.V = " + num(c.test.n_dot_v) +
            (c.test.back ? " <= 0: back face" : " > 0: front face") + " -> culled\n";
    for (const FragmentRecord* r : records) {
      text += "      exact: snapped signed area (doubled, 1/256 px units) " + std::to_string(r->fixed_area) + ", " +
              (r->front_facing ? "front" : "back") + "-facing";
      if (r->clipped)
        text += " (clip piece " + std::to_string(r->clip_piece + 1) + "/" + std::to_string(r->clip_pieces) + ")";
      text += r->cull == CullReason::Facing ? " -> culled\n"
              : r->cull == CullReason::None
                  ? " -> kept, " + std::string(r->covered ? "covers" : "does not cover") + " the sample\n"
                  : " -> dropped for another reason (see the exact block)\n";
    }
    if (records.empty()) text += "      exact: no record at this pixel (its set-up box misses the pixel)\n";
  }
  if (text.empty()) return "";
  return "  cull=normal_dot_view removed near the pixel (before clipping; N = (v1 - v0) x (v2 - v0) of the clip points "
         "(x, y, w), V = eye - v0 with the eye at the origin; back face: N.V <= 0):\n" +
         text;
}

std::string painter_text(const std::vector<ClassicPrimitive>& primitives, const std::vector<size_t>& at_pixel) {
  const std::vector<PainterKeyed> keyed = painter_keys(primitives);
  std::string text =
      "  visibility=painter: sort key = the farthest vertex's window z (methods::painter_key), larger keys painted "
      "first (ties in submission order), no depth test; the triangles painted at this pixel, in painting order:\n";
  for (size_t position = 0; position < keyed.size(); ++position) {
    const size_t i = keyed[position].primitive;
    if (std::find(at_pixel.begin(), at_pixel.end(), i) == at_pixel.end()) continue;
    text += "    " + primitive_name(i, primitives[i]) + ": key " + num(keyed[position].key) + ", painted " +
            ordinal(position + 1) + " of " + std::to_string(keyed.size()) +
            (i == at_pixel.back() ? " (last here: the owner)" : "") + "\n";
  }
  return text;
}

std::string bsp_text(const std::vector<ClassicPrimitive>& primitives, const std::vector<size_t>& at_pixel,
                     const PixelState& pixel) {
  const BspPixelTrace trace = bsp_pixel_trace(primitives, at_pixel, pixel.x, pixel.y);
  std::string text = "  visibility=bsp: a tree of " + std::to_string(trace.nodes) + " node(s), " +
                     std::to_string(trace.splits) + " split(s), " + std::to_string(trace.polygons) +
                     " piece(s) drawn back to front for the viewer at z = -infinity (0, 0, -1, 0); at each node the "
                     "side away from the viewer first, then the node, then the viewer's side. The pieces painted at "
                     "this pixel:\n";
  for (const BspPieceTrace& piece : trace.pieces) {
    text += "    " + primitive_name(piece.primitive, primitives[piece.primitive]);
    if (piece.path.empty()) {
      text += ": no area in window space, not in the tree\n";
      continue;
    }
    text += ": piece rank " + std::to_string(piece.rank + 1) + " of " + std::to_string(trace.polygons) + " (" +
            std::to_string(piece.pieces) + " piece(s) of it in the tree)\n";
    for (const BspNodeTest& node : piece.path) {
      text += "      node " + std::to_string(node.node) + " (plane of #" + std::to_string(node.partition) + ": n " +
              vec3_text(node.plane.normal) + ", d " + num(node.plane.d) + "): viewer side " + num(node.viewer_side) +
              (node.viewer_side > 0 ? " > 0, eye in front: behind drawn first"
                                    : " <= 0, eye behind: in front drawn first") +
              "; the piece " +
              (node.path < 0   ? "is behind"
               : node.path > 0 ? "is in front"
                               : "is at this node") +
              "\n";
    }
  }
  return text;
}

// The exact path at the same sample (the reference): its records and final value.
struct ExactSide {
  std::vector<FragmentRecord> records;
  uint32_t owner = kOwnerBackground;
  bool has_depth = false;
  uint32_t depth_raw = 0;
};

ExactSide exact_side(const Scene& scene, const CpuOptions& options, uint32_t x, uint32_t y, uint32_t sample) {
  CpuOptions exact = options;
  exact.methods.clear();  // every stage exact, z-buffer: the lavapipe model
  ExactSide side;
  side.records = explain_pixel(scene, exact, x, y, sample);
  const RenderResult render = render_exact(scene, exact);
  const size_t i = render.index(x, y, sample);
  side.owner = render.owner[i];
  side.has_depth = render.has_depth();
  if (side.has_depth) side.depth_raw = render.depth_raw[i];
  return side;
}

std::string differ_text(const PixelState& pixel, const ExactSide& exact, bool has_depth) {
  std::vector<std::string> parts;
  if (pixel.owner != exact.owner)
    parts.push_back("owner: method " + owner_words(pixel.owner) + ", exact " + owner_words(exact.owner));
  if (has_depth && exact.has_depth && pixel.stored != exact.depth_raw)
    parts.push_back("depth raw: method " + hex(pixel.stored) + ", exact " + hex(exact.depth_raw));
  if (parts.empty()) return "differ: nowhere at this sample (same owner and raw depth)\n";
  std::string text = "differ: ";
  for (size_t k = 0; k < parts.size(); ++k) text += (k ? "; " : "") + parts[k];
  return text + "\n";
}

}  // namespace

std::string explain_classic_pixel(const Scene& scene, const CpuOptions& options, uint32_t x, uint32_t y,
                                  uint32_t sample) {
  if (x >= scene.width || y >= scene.height || sample >= scene.samples)
    throw UsageError("explain: pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") sample " +
                     std::to_string(sample) + " is outside the " + std::to_string(scene.width) + "x" +
                     std::to_string(scene.height) + " framebuffer with " + std::to_string(scene.samples) +
                     " sample(s)");
  const cpu::DenormalsFlushed ftz_daz;  // as render_classic (rules §7.10)
  const ClassicFrame prepared = prepare_classic_frame(scene, options, true);
  const ExactSide exact = exact_side(scene, options, x, y, sample);
  const ClassicMethods& chosen = prepared.chosen;
  const std::vector<ClassicPrimitive>& primitives = prepared.primitives;
  const std::string fill = choice_of(options, "fill", "exact"), line = choice_of(options, "line", "exact");
  const std::string depth = choice_of(options, "depth", "exact");
  const std::string visibility = choice_of(options, "visibility", "zbuffer");
  const std::string clip = choice_of(options, "clip", "exact");

  PixelState pixel{int32_t(x), int32_t(y), sample, 0, kOwnerBackground};
  pixel.stored = scene.has_depth() ? cpu::clear_depth_raw(scene.depth_format, scene.depth_clear) : 0;
  std::string text = "method (judged): classic path, methods" + methods_line(options) + "\n" +
                     std::to_string(primitives.size()) +
                     " primitive(s) reached the fill and line stages after clip=" + clip +
                     " and cull=" + choice_of(options, "cull", "exact") +
                     "; those near the pixel, in the order visibility=" + visibility + " draws them:\n";
  const auto fragments_of = [&](const ClassicPrimitive& p) {
    std::vector<Fragment> fragments;
    for_each_fragment(p, chosen, prepared.frame.region, [&](const Fragment& f) { fragments.push_back(f); });
    return fragments;
  };
  const auto at_pixel = [&](const std::vector<Fragment>& fragments) -> std::optional<size_t> {
    for (size_t k = 0; k < fragments.size(); ++k)
      if (fragments[k].x == pixel.x && fragments[k].y == pixel.y) return k;
    return std::nullopt;
  };
  const auto clip_text = [&](const ClassicPrimitive& p) {
    if (p.line_clip_traced) return line_clip_text(p, clip);
    if (p.vertex_codes_traced) return triangle_clip_text(p, clip);
    return std::string();
  };
  size_t listed = 0;
  if (chosen.visibility == VisibilityMethod::ZBuffer) {
    for (size_t i = 0; i < primitives.size(); ++i) {
      const ClassicPrimitive& p = primitives[i];
      if (!chosen.per_pixel()) {
        if (!primitive_near(p, pixel.x, pixel.y)) continue;
        text += primitive_line(i, p) + clip_text(p) + exact_history(p, chosen, pixel);
        ++listed;
        continue;
      }
      const std::vector<Fragment> fragments = fragments_of(p);
      const std::optional<size_t> at = at_pixel(fragments);
      if (!at && !primitive_near(p, pixel.x, pixel.y)) continue;
      ++listed;
      text += primitive_line(i, p) + clip_text(p) +
              coverage_text(p, chosen, fill, line, prepared.frame.region, pixel, fragments, at);
      if (!at) continue;
      bool passed = true;
      text += "    " + depth_method_text(p, chosen, depth, pixel) +
              depth_test_text(p, fragments[*at].depth_raw, true, pixel, passed) + "\n";
      if (passed) pixel.owner = p.raster.owner;
      text += std::string("    owner ") + (passed ? "written" : "kept") + "\n";
    }
  } else {
    // Painting order: every fragment of the frame back to front; those at this pixel overwrite.
    const std::vector<PaintedFragment> painted_frame =
        back_to_front_fragments(primitives, chosen, prepared.frame.region);
    std::vector<std::pair<size_t, const PaintedFragment*>> here;  // rank (1-based), fragment
    std::vector<size_t> painted_here;
    for (size_t rank = 0; rank < painted_frame.size(); ++rank) {
      const PaintedFragment& painted = painted_frame[rank];
      if (painted.fragment.x != pixel.x || painted.fragment.y != pixel.y) continue;
      here.push_back({rank + 1, &painted});
      painted_here.push_back(painted.primitive);
    }
    if (!painted_here.empty())
      text += chosen.visibility == VisibilityMethod::Painter ? painter_text(primitives, painted_here)
                                                             : bsp_text(primitives, painted_here, pixel);
    for (const auto& [rank, painted] : here) {
      const ClassicPrimitive& p = primitives[painted->primitive];
      const std::vector<Fragment> fragments = fragments_of(p);
      text += primitive_line(painted->primitive, p) + clip_text(p) +
              coverage_text(p, chosen, fill, line, prepared.frame.region, pixel, fragments, at_pixel(fragments));
      text += "    visibility=" + visibility + ": painted as fragment " + std::to_string(rank) + " of " +
              std::to_string(painted_frame.size()) +
              " in the frame's back-to-front order (window z, larger is farther)\n";
      bool passed = true;
      text += "    " + depth_method_text(p, chosen, depth, pixel) +
              depth_test_text(p, painted->fragment.depth_raw, false, pixel, passed) + "\n    owner written\n";
      pixel.owner = p.raster.owner;
      ++listed;
    }
  }
  if (listed == 0) text += "  none\n";
  if (chosen.cull == CullMethod::NormalDotView) text += culled_text(prepared, exact.records, pixel);
  text += "classic result: owner " + owner_words(pixel.owner);
  if (scene.has_depth()) text += ", depth raw " + hex(pixel.stored);
  text +=
      "\nexact (reference): the exact path at the same sample, every stage exact with the z-buffer (the lavapipe "
      "model), every primitive that reached the pixel in submission order:\n" +
      format_explanation(exact.records) + "exact result: owner " + owner_words(exact.owner);
  if (scene.has_depth() && exact.has_depth) text += ", depth raw " + hex(exact.depth_raw);
  return text + "\n" + differ_text(pixel, exact, scene.has_depth());
}

}  // namespace rastercmp
