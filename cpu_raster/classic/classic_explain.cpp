#include "cpu_raster/classic/classic_explain.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "cpu_raster/classic/classic_fragments.hpp"
#include "cpu_raster/classic/classic_visibility.hpp"
#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/rasterize.hpp"
#include "model/errors.hpp"
#include "model/render_result.hpp"

namespace rastercmp {
namespace {

using namespace cpu::classic;

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  return buffer;
}

std::string hex(uint32_t v) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%#x", v);
  return buffer;
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

std::string primitive_line(size_t index, const ClassicPrimitive& p) {
  std::string text = "  #" + std::to_string(index) + " draw " + std::to_string(p.draw_index) + " primitive " +
                     std::to_string(p.primitive_index) + (p.is_line ? " line" : " triangle");
  if (p.clipped || p.pieces > 1)
    text += " (clip piece " + std::to_string(p.piece + 1) + "/" + std::to_string(p.pieces) + ")";
  text += ", window";
  const size_t n = p.is_line ? 2 : 3;
  for (size_t k = 0; k < n; ++k)
    text += " (" + num(p.window[k].x) + ", " + num(p.window[k].y) + ", z " + num(p.window[k].z) + ", w " +
            num(p.w_clip[k]) + ")";
  return text + "\n";
}

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

// Whether the primitive's window extent (or the coverage) comes near the pixel.
bool near_pixel(const ClassicPrimitive& p, int32_t x, int32_t y) {
  const size_t n = p.is_line ? 2 : 3;
  double x0 = p.window[0].x, x1 = x0, y0 = p.window[0].y, y1 = y0;
  for (size_t k = 1; k < n; ++k) {
    x0 = std::fmin(x0, p.window[k].x), x1 = std::fmax(x1, p.window[k].x);
    y0 = std::fmin(y0, p.window[k].y), y1 = std::fmax(y1, p.window[k].y);
  }
  return x + 1 >= x0 && x <= x1 && y + 1 >= y0 && y <= y1;
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

// The exact rasterizer's history (fill and line exact, depth exact or no_fma, zbuffer).
std::string exact_history(const ClassicPrimitive& p, const ClassicMethods& chosen, PixelState& pixel) {
  cpu::DepthTestState depth = p.depth;
  if (chosen.depth == DepthMethod::NoFma) depth.fma = false;
  const uint32_t tested = p.raster.per_sample ? pixel.sample : 0;
  const cpu::SampleVerdict verdict = cpu::evaluate_sample(p.raster, depth, pixel.x, pixel.y, tested, pixel.stored);
  std::string text = "    coverage (24.8 edge planes, top-left rule) at sample " + std::to_string(tested) + ": E";
  for (uint32_t i = 0; i < p.raster.planes.count; ++i) {
    text += ' ';
    text += std::to_string(cpu::edge_value(p.raster.planes.plane[i], verdict.point.x_fixed, verdict.point.y_fixed));
  }
  const bool covered = verdict.covered() && p.raster.visit.contains(pixel.x, pixel.y);
  if (covered)
    text += " -> covered\n";
  else if (!verdict.covered())
    text += " -> not covered (plane " + std::to_string(verdict.failing_plane) + " fails)\n";
  else
    text += " -> not covered (the rasterizer does not visit the pixel)\n";
  if (!covered) return text;
  bool passed = true;
  text += "    depth (" + std::string(chosen.depth == DepthMethod::NoFma ? "no_fma" : "exact") + " plane): z " +
          num(verdict.depth.interpolated) + ", " + depth_test_text(p, verdict.depth.raw, true, pixel, passed) + "\n";
  if (passed) pixel.owner = p.raster.owner;
  return text + "    owner " + (passed ? "written" : "kept") + "\n";
}

std::string coverage_text(const ClassicPrimitive& p, const ClassicMethods& chosen, const std::string& fill,
                          const std::string& line, const cpu::PixelRect& region, const PixelState& pixel,
                          const std::vector<Fragment>& fragments, std::optional<size_t> at) {
  if (p.is_line) {
    std::string text = "    line=" + line + ": ";
    if (chosen.line == LineMethod::Exact)
      return text + "row " + std::to_string(pixel.y) + " pixels" + row_spans(fragments, pixel.y) +
             (at ? " -> covered\n" : " -> not covered\n");
    text += "pixels from (" + std::to_string(int32_t(std::floor(p.window[0].x))) + ", " +
            std::to_string(int32_t(std::floor(p.window[0].y))) + ") to (" +
            std::to_string(int32_t(std::floor(p.window[1].x))) + ", " +
            std::to_string(int32_t(std::floor(p.window[1].y))) + "), " + std::to_string(fragments.size()) +
            " in the region";
    return text + (at ? ", this pixel is step " + std::to_string(*at) + " -> covered\n" : "; not this pixel\n");
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
  return text + (at ? " -> covered\n" : " -> not covered\n");
}

std::string depth_method_text(const ClassicPrimitive& p, const ClassicMethods& chosen, const std::string& depth,
                              const PixelState& pixel) {
  if (chosen.depth == DepthMethod::PseudoDepth)
    return "depth=" + depth + ": (1 - pz) / 2 = " + num(pseudo_depth_value(p, chosen.pseudo_far, pixel.x, pixel.y)) +
           " (near 25, far " + num(chosen.pseudo_far) + "), ";
  if (p.is_line && chosen.depth != DepthMethod::NoFma) return "depth=" + depth + " (lines take the plane): ";
  return "depth=" + depth + ": ";
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
  const ClassicFrame prepared = prepare_classic_frame(scene, options);
  const ClassicMethods& chosen = prepared.chosen;
  const std::vector<ClassicPrimitive>& primitives = prepared.primitives;
  const std::string fill = choice_of(options, "fill", "exact"), line = choice_of(options, "line", "exact");
  const std::string depth = choice_of(options, "depth", "exact");
  const std::string visibility = choice_of(options, "visibility", "zbuffer");

  PixelState pixel{int32_t(x), int32_t(y), sample, 0, kOwnerBackground};
  pixel.stored = scene.has_depth() ? cpu::clear_depth_raw(scene.depth_format, scene.depth_clear) : 0;
  std::string text =
      "classic path, methods" + methods_line(options) + "\n" + std::to_string(primitives.size()) +
      " primitive(s) reached the fill and line stages after clip=" + choice_of(options, "clip", "exact") +
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
  size_t listed = 0;
  if (chosen.visibility == VisibilityMethod::ZBuffer) {
    for (size_t i = 0; i < primitives.size(); ++i) {
      const ClassicPrimitive& p = primitives[i];
      if (!chosen.per_pixel()) {
        if (!near_pixel(p, pixel.x, pixel.y)) continue;
        text += primitive_line(i, p) + exact_history(p, chosen, pixel);
        ++listed;
        continue;
      }
      const std::vector<Fragment> fragments = fragments_of(p);
      const std::optional<size_t> at = at_pixel(fragments);
      if (!at && !near_pixel(p, pixel.x, pixel.y)) continue;
      ++listed;
      text += primitive_line(i, p) + coverage_text(p, chosen, fill, line, prepared.frame.region, pixel, fragments, at);
      if (!at) continue;
      bool passed = true;
      text += "    " + depth_method_text(p, chosen, depth, pixel) +
              depth_test_text(p, fragments[*at].depth_raw, true, pixel, passed) + "\n";
      if (passed) pixel.owner = p.raster.owner;
      text += std::string("    owner ") + (passed ? "written" : "kept") + "\n";
    }
  } else {
    // Painting order: every fragment of the frame back to front; those at this pixel overwrite.
    size_t rank = 0;
    for (const PaintedFragment& painted : back_to_front_fragments(primitives, chosen, prepared.frame.region)) {
      ++rank;
      if (painted.fragment.x != pixel.x || painted.fragment.y != pixel.y) continue;
      const ClassicPrimitive& p = primitives[painted.primitive];
      const std::vector<Fragment> fragments = fragments_of(p);
      text += primitive_line(painted.primitive, p) +
              coverage_text(p, chosen, fill, line, prepared.frame.region, pixel, fragments, at_pixel(fragments));
      text += "    visibility=" + visibility + ": painted as fragment " + std::to_string(rank) +
              " of the frame's back-to-front order (window z, larger is farther)\n";
      bool passed = true;
      text += "    " + depth_method_text(p, chosen, depth, pixel) +
              depth_test_text(p, painted.fragment.depth_raw, false, pixel, passed) + "\n    owner written\n";
      pixel.owner = p.raster.owner;
      ++listed;
    }
  }
  if (listed == 0) text += "  none\n";
  text += "classic result: owner ";
  text += pixel.owner == kOwnerBackground ? std::string("background")
                                          : "draw " + std::to_string(owner_draw(pixel.owner)) + " primitive " +
                                                std::to_string(owner_primitive(pixel.owner));
  if (scene.has_depth()) text += ", depth raw " + hex(pixel.stored);
  return text + "\n";
}

}  // namespace rastercmp
