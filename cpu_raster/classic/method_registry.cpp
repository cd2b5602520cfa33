#include "cpu_raster/classic/method_registry.hpp"

#include <cmath>
#include <string>

#include "model/errors.hpp"

namespace rastercmp::cpu::classic {
namespace {

constexpr std::string_view kLavapipe = "";  // lavapipe's own rule: no section of the notes

const std::vector<StageInfo> kStages{
    {"clip", "cut primitives to the clip volume (3-D methods before the divide, 2-D ones in window space)"},
    {"cull", "drop back-facing triangles"},
    {"fill", "which pixels a triangle covers"},
    {"line", "which pixels a line covers"},
    {"depth", "the depth value stored for a covered pixel"},
    {"visibility", "which fragment of a pixel is seen"},
    {"snap", "exact path ablation: rounding of window coordinates to 24.8 fixed point"},
    {"tie_break", "exact path ablation: which edges own the samples exactly on them"},
};

const std::vector<MethodInfo> kMethods{
    {"clip", "exact", "lavapipe's clipper (guard band, float plane crossings)", kLavapipe,
     "docs/lavapipe-rules.md §1.6"},
    {"clip", "cohen_sutherland", "lines: 4-bit outcodes against the viewport rectangle, after the divide",
     "Cohen-Sutherland Algorithm; Line Clipping", "Cohen–Sutherland (2D)"},
    {"clip", "cohen_sutherland_3d", "lines: 6-bit outcodes against the homogeneous clip volume",
     "Cohen Sutherland in 3D", "Cohen–Sutherland (3D, 6-bit outcodes)"},
    {"clip", "liang_barsky", "lines: entering / leaving parameters on the six homogeneous planes, one pass",
     "Liang-Barsky Clipping", "Liang–Barsky"},
    {"clip", "cyrus_beck", "lines: N·(p - pE) parameters against the viewport as a convex polygon, after the divide",
     "Cyrus-Beck Algorithm", "Cyrus–Beck"},
    {"clip", "sutherland_hodgman", "triangles: one homogeneous plane at a time, fanned",
     "Pipeline Clipping of Polygons", "Sutherland–Hodgman"},
    {"clip", "weiler_atherton", "triangles: polygon against the viewport polygon, after the divide, fanned",
     "Clipping algorithms (Weiler-Atherton, poly vs poly); Polygon Clipping", "Weiler–Atherton"},
    {"cull", "exact", "the sign of the snapped window-space area (and lavapipe's float cull)", kLavapipe,
     "docs/lavapipe-rules.md §2.3"},
    {"cull", "normal_dot_view", "N·V in homogeneous clip space before clipping", "Back Face Removal",
     "Back-face culling"},
    {"fill", "exact", "24.8 edge functions with the top-left rule", kLavapipe, "docs/lavapipe-rules.md §2.4"},
    {"fill", "scanline", "the notes' scanline fill (ignore horizontal edges and top vertices)",
     "Polygon Filling - Approach; Pseudo-Code", "The notes' scanline fill"},
    {"fill", "even_odd", "parity of boundary crossings at pixel centres", "Polygon Scan Conversion (odd-even test)",
     "Even-odd and non-zero winding fill"},
    {"fill", "winding", "non-zero winding number at pixel centres", "Polygon Scan Conversion (winding number)",
     "Even-odd and non-zero winding fill"},
    {"fill", "float_edge", "float edge functions at pixel centres, no snapping, no tie rule", "Rasterizing a Triangle",
     "Float edge-function fill"},
    {"fill", "flood", "Bresenham outline, then a 4-connected flood fill from a seed inside", "Flood Fill",
     "Flood fill"},
    {"line", "exact", "Vulkan's line modes (lavapipe's line set-up)", kLavapipe, "docs/lavapipe-rules.md §4"},
    {"line", "dda", "1-pixel line stepping y += k per x (or x per y)", "DDA Algorithm; Using Symmetry", "DDA"},
    {"line", "bresenham", "1-pixel integer line with the error term", "Complete Bresenham's line drawing algorithm",
     "Bresenham"},
    {"depth", "exact", "lavapipe's depth plane, fused as --fma says", kLavapipe, "docs/lavapipe-rules.md §3.3"},
    {"depth", "no_fma", "the same plane, every product and sum rounded on its own", "Interpolate Z-value",
     "Depth plane without fused multiply-add"},
    {"depth", "bilinear", "interpolate up the edges, then across the span", "Bilinear interpolation",
     "Bilinear depth interpolation"},
    {"depth", "perspective_correct", "window z weighted by 1/w (z/w and 1/w interpolated)", "Using Interpolation",
     "Perspective-correct interpolation"},
    {"depth", "pseudo_depth_75", "the notes' pseudo-depth of the eye distance w, near 25, far 75",
     "Pseudo-depth; pz At near and far", "Pseudo-depth"},
    {"depth", "pseudo_depth_750", "the notes' pseudo-depth of the eye distance w, near 25, far 750",
     "Pseudo-depth; pz At near and far", "Pseudo-depth"},
    {"depth", "pseudo_depth_7500", "the notes' pseudo-depth of the eye distance w, near 25, far 7500",
     "Pseudo-depth; pz At near and far", "Pseudo-depth"},
    {"visibility", "zbuffer", "the depth test, primitives in order", "The Z-Buffer Algorithm",
     "Z-buffer (the reference for painter's and BSP)"},
    {"visibility", "painter", "triangles sorted by farthest window z, painted back to front", "Painter's Algorithm",
     "Painter's algorithm"},
    {"visibility", "bsp", "window-space BSP tree traversed back to front", "Polygon-aligned BSP tree", "BSP tree"},
    {"snap", "round_nearest_even", "lavapipe's rounding to 1/256 pixel", kLavapipe,
     "docs/cpu-raster.md \"Method switches (ablations)\""},
    {"snap", "round_half_away", "ties rounded away from zero", kLavapipe,
     "docs/cpu-raster.md \"Method switches (ablations)\""},
    {"tie_break", "top_left", "left and top edges own their samples", kLavapipe,
     "docs/cpu-raster.md \"Method switches (ablations)\""},
    {"tie_break", "none", "no edge owns its samples (E > 0 only)", kLavapipe,
     "docs/cpu-raster.md \"Method switches (ablations)\""},
};

bool is_one_of(std::string_view name, std::initializer_list<std::string_view> names) {
  for (std::string_view n : names)
    if (name == n) return true;
  return false;
}

// Methods that decide coverage or depth for one sample per pixel.
bool decides_per_pixel(const MethodChoice& c) {
  if (c.stage == "fill" || c.stage == "line") return c.name != "exact";
  if (c.stage == "depth") return c.name != "exact" && c.name != "no_fma";
  if (c.stage == "visibility") return c.name != "zbuffer";
  return false;
}

std::string label(const MethodChoice& c) { return c.stage + "=" + c.name; }
std::string draw_path(size_t d) { return "$.draws[" + std::to_string(d) + "]"; }

std::optional<std::string> lines_only_drawn(const Scene& scene, const MethodChoice& c, std::string_view what) {
  for (size_t d = 0; d < scene.draws.size(); ++d)
    if (is_line_topology(scene.draws[d].topology))
      return label(c) + " " + std::string(what) + "; " + draw_path(d) + " draws lines";
  return std::nullopt;
}

// 2-D clippers work after the divide: every vertex in front of the eye and, with depth clip, inside
// 0 <= z <= w, so only x and y are left to clip.
std::optional<std::string> needs_2d_clip(const Scene& scene, const MethodChoice& c, bool lines) {
  for (size_t d = 0; d < scene.draws.size(); ++d) {
    const Draw& draw = scene.draws[d];
    if (is_line_topology(draw.topology) != lines) continue;
    for (size_t k = 0; k < draw.positions_clip.size(); ++k) {
      const glm::vec4& p = draw.positions_clip[k];
      const std::string where = draw_path(d) + ".positions[" + std::to_string(k) + "]";
      if (!(p.w > 0))
        return label(c) + " clips in 2-D after the divide; " + where + " has w = " + std::to_string(p.w) +
               " (not in front of the eye)";
      if (draw.state.depth_clip_enabled() && !(p.z >= 0 && p.z <= p.w))
        return label(c) + " clips x and y only; " + where +
               " lies outside the depth clip planes 0 <= z <= w (z = " + std::to_string(p.z) +
               ", w = " + std::to_string(p.w) + ")";
    }
  }
  return std::nullopt;
}

}  // namespace

const std::vector<StageInfo>& method_stages() { return kStages; }
const std::vector<MethodInfo>& method_registry() { return kMethods; }

const MethodInfo* find_method(std::string_view stage, std::string_view name) {
  for (const MethodInfo& m : kMethods)
    if (m.stage == stage && m.name == name) return &m;
  return nullptr;
}

std::string method_names(std::string_view stage) {
  std::string names;
  for (const MethodInfo& m : kMethods)
    if (m.stage == stage) names += (names.empty() ? "" : ", ") + std::string(m.name);
  return names;
}

std::string stage_names() {
  std::string names;
  for (const StageInfo& s : kStages) names += (names.empty() ? "" : ", ") + std::string(s.stage);
  return names;
}

void check_method_choice(const MethodChoice& choice) {
  if (find_method(choice.stage, choice.name)) return;
  const std::string known = method_names(choice.stage);
  if (known.empty())
    throw UsageError("method " + label(choice) + ": unknown stage \"" + choice.stage +
                     "\"; known stages: " + stage_names() + " (rastercmp methods lists every name)");
  throw UsageError("method " + label(choice) + ": unknown name for stage \"" + choice.stage + "\"; known: " + known);
}

double pseudo_depth_far(std::string_view name) {
  if (name == "pseudo_depth_75") return 75;
  if (name == "pseudo_depth_750") return 750;
  if (name == "pseudo_depth_7500") return 7500;
  return 0;
}

double pseudo_depth_step_at_far(double far_distance, int bits) {
  return (far_distance - kPseudoDepthNear) * far_distance / (kPseudoDepthNear * (std::ldexp(1.0, bits) - 1));
}

std::optional<std::string> method_inapplicable(const Scene& scene, const MethodChoice& c) {
  if (!find_method(c.stage, c.name)) return std::nullopt;
  if (decides_per_pixel(c) && scene.samples != 1)
    return label(c) + " decides one sample per pixel; the scene has " + std::to_string(scene.samples) + " samples";
  if (c.stage == "line" && (c.name == "dda" || c.name == "bresenham")) {
    for (size_t d = 0; d < scene.draws.size(); ++d)
      if (is_line_topology(scene.draws[d].topology) && scene.draws[d].state.line_width != 1)
        return label(c) + " draws 1-pixel lines; " + draw_path(d) + " has line_width " +
               std::to_string(scene.draws[d].state.line_width);
  }
  if (c.stage == "visibility" && c.name != "zbuffer")
    return lines_only_drawn(scene, c, "orders triangles only (a line has no plane to sort or split by)");
  if (c.stage == "clip" && is_one_of(c.name, {"cohen_sutherland", "cyrus_beck"})) return needs_2d_clip(scene, c, true);
  if (c.stage == "clip" && c.name == "weiler_atherton") return needs_2d_clip(scene, c, false);
  if (c.stage == "depth") {
    const double far_distance = pseudo_depth_far(c.name);
    if (far_distance == 0) return std::nullopt;
    for (size_t d = 0; d < scene.draws.size(); ++d)
      for (size_t k = 0; k < scene.draws[d].positions_clip.size(); ++k) {
        const float w = scene.draws[d].positions_clip[k].w;
        if (!(w >= kPseudoDepthNear && w <= far_distance))
          return label(c) + " takes the eye distance w between the notes' near 25 and far " +
                 std::to_string(int(far_distance)) + "; " + draw_path(d) + ".positions[" + std::to_string(k) +
                 "] has w = " + std::to_string(w);
      }
  }
  return std::nullopt;
}

}  // namespace rastercmp::cpu::classic
