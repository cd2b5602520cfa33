#include "experiments/method_maps.hpp"

#include <algorithm>
#include <cmath>


#include "cpu_raster/classic/method_registry.hpp"
#include "experiments/method_map_scenes.hpp"
#include "experiments/scene_make.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {
namespace {

// docs/methods.md "Where it fails" of each family; the notes' sections by their titles.
const std::vector<MapExperiment> kExperiments{
    {"fill_sliver_width", "fill", "sliver width at its wide end (sub-pixels)", "any_mismatch",
     "CFZ Polygon Filling: slivers lose or gain pixel centres"},
    {"fill_fan", "fill", "shared vertex offset from a pixel centre (sub-pixels)", "any_mismatch",
     "RDS Rasterizing a Triangle: shared edges and fans hit samples on the edge"},
    {"fill_distance", "fill", "window x of the far vertex (pixels)", "any_mismatch",
     "float edge functions against 24.8 fixed point far from the origin"},
    {"clip_near_w", "clip", "clip w of a vertex on the near plane", "any_mismatch",
     "RDS Cohen Sutherland in 3D, Pipeline Clipping of Polygons: w -> 0"},
    {"clip_near_w_line", "clip", "clip w of a line end on the near plane", "any_mismatch",
     "NLC Line Clipping, RDS Liang-Barsky, GPC Cyrus-Beck: w -> 0"},
    {"clip_near_cross", "clip", "distance of a vertex behind the near plane (clip z units)", "any_mismatch",
     "DCP Clipping algorithms: the near plane cuts the primitive"},
    {"depth_far_near", "depth", "far / near", "value_cpu",
     "DCP z-fighting: depth precision falls with far/near (per format; reversed Z)"},
    {"pseudo_depth", "depth", "separation of the pair (world units)", "value_cpu",
     "CFZ Pseudo-depth, pz At near and far: one step spans (far-near) far / (near (2^n - 1)) at far"},
    {"coplanar_offset", "depth", "constant polygon offset (r units, pulling the decal)", "value_cpu",
     "DCP Polygon offset: coplanar pairs fight until the offset exceeds the rounding"},
    {"visibility_cyclic", "visibility", "tilt of three bars in a cyclic overlap (window depth)", "any_mismatch",
     "RDS Painter's Algorithm, Hard Cases: cyclic overlap"},
    {"visibility_interpenetration", "visibility", "penetration of one square through another (window depth)",
     "any_mismatch", "RDS Painter's Algorithm, Hard Cases: interpenetration"},
    {"line_slope", "line", "slope of a 40-pixel line, ends at pixel centres (degrees)", "excess_mismatch",
     "RDS DDA Algorithm, Bresenham's line drawing algorithm: integer ends, one pixel per column", true},
    {"line_end_offset", "line", "offset of the line's end from its pixel centre, across the line (sub-pixels)",
     "excess_mismatch", "RDS DDA, Bresenham: the ends are pixels; the real line moves off them", true},
    {"line_length", "line", "length of a line of slope 1/3, ends at pixel centres (pixels)", "excess_mismatch",
     "RDS DDA, Bresenham: both end pixels drawn, against Vulkan's end rules"},
    {"cull_edge_on", "cull", "angle of the face's normal to the view axis (degrees)", "any_mismatch",
     "NLC Back Face Removal: N.V <= 0 against the sign of the snapped window area", true},
};

std::vector<double> pick(bool quick, std::vector<double> small, std::vector<double> full) {
  return quick ? small : full;
}

CpuOptions with_method(const std::string& stage, const std::string& name) {
  CpuOptions cpu = exact_cpu_options();
  cpu.methods = {{stage, name}};
  return cpu;
}

std::vector<NamedMethod> named(std::initializer_list<std::pair<const char*, const char*>> choices) {
  std::vector<NamedMethod> out{{"exact", exact_cpu_options()}};
  for (const auto& [stage, name] : choices) out.push_back({std::string(stage) + "=" + name, with_method(stage, name)});
  return out;
}

std::vector<NamedMethod> line_clip_methods() {
  return named({{"clip", "cohen_sutherland"}, {"clip", "cohen_sutherland_3d"}, {"clip", "liang_barsky"},
                {"clip", "cyrus_beck"}});
}

std::vector<NamedMethod> pseudo_depth_methods() {
  return {{"depth=pseudo_depth_75", with_method("depth", "pseudo_depth_75")},
          {"depth=pseudo_depth_750", with_method("depth", "pseudo_depth_750")},
          {"depth=pseudo_depth_7500", with_method("depth", "pseudo_depth_7500")}};
}

void add_series(std::vector<StabilityPoint>& plan, const char* experiment, const std::string& case_name,
                const std::vector<NamedMethod>& methods, const std::vector<double>& params,
                const std::function<Scene(double)>& make, bool wrong_surface = false) {
  for (const auto& [label, cpu] : methods)
    for (double p : params)
      plan.push_back({experiment, case_name, label, p, 0, [make, p] { return make(p); }, cpu,
                      wrong_surface ? 1u : 0u, wrong_surface});
}

void add_fill(std::vector<StabilityPoint>& plan, bool quick) {
  const std::vector<NamedMethod> methods = fill_methods();
  add_series(plan, "fill_sliver_width", "sliver_strip", methods,
             pick(quick, {256, 64, 4, 1, 0.5}, {256, 128, 64, 32, 16, 8, 4, 2, 1, 0.5, 0.25}), make_sliver_strip);
  add_series(plan, "fill_fan", "fan", methods, pick(quick, {16, 1, 0.5, 0}, {64, 32, 16, 8, 4, 2, 1, 0.5, 0.25, 0}),
             make_fan);
  add_series(plan, "fill_distance", "far_triangle", methods,
             pick(quick, {64, 4096, 32767}, {64, 256, 1024, 4096, 8192, 16384, 24576, 32767}), make_far_triangle);
}

void add_clip(std::vector<StabilityPoint>& plan, bool quick) {
  const std::vector<double> ws = pick(quick, {1, 1e-3, 1e-20, 0, -1e-6},
                                      {1, 1e-1, 1e-2, 1e-3, 1e-5, 1e-8, 1e-12, 1e-20, 1e-30, 1e-38, 0, -1e-6});
  const std::vector<NamedMethod> triangle = named({{"clip", "sutherland_hodgman"}, {"clip", "weiler_atherton"}});
  add_series(plan, "clip_near_w", "triangle", triangle, ws, [](double w) { return make_near_w_triangle(float(w)); });
  add_series(plan, "clip_near_w_line", "line", line_clip_methods(), ws,
             [](double w) { return make_near_w_line(float(w)); });
  const std::vector<double> behind = pick(quick, {0, 1e-4, 1, 1e4}, {0, 1e-6, 1e-4, 1e-2, 1, 100, 1e4, 1e6});
  add_series(plan, "clip_near_cross", "triangle", triangle, behind, make_near_cross_triangle);
  add_series(plan, "clip_near_cross", "line", line_clip_methods(), behind, make_near_cross_line);
}

// Powers 10^(k/steps) for k from `from` to `to` (either direction), `stride` apart.
std::vector<double> powers(int from, int to, int stride, double steps) {
  std::vector<double> out;
  for (int k = from; from <= to ? k <= to : k >= to; k += from <= to ? stride : -stride)
    out.push_back(std::pow(10.0, k / steps));
  return out;
}

void add_depth(std::vector<StabilityPoint>& plan, bool quick) {
  const std::vector<NamedMethod> methods =
      named({{"depth", "no_fma"}, {"depth", "bilinear"}, {"depth", "perspective_correct"}});
  const std::vector<double> ratios = powers(4, 24, quick ? 2 : 1, 4);  // 10 .. 10^6
  // Each format with each clip-z mapping: standard or reversed, formed in float (as a camera
  // matrix does) or in double from w (scene_make.hpp DepthMapping).
  for (DepthMapping mapping : kDepthMappings)
    for (DepthFormat format : sweep_depth_formats())
      add_series(
          plan, "depth_far_near", std::string(to_string(format)) + mapping_suffix(mapping), methods, ratios,
          [format, mapping](double ratio) {
            PairParams p;
            p.kind = PairKind::NearCoplanar;
            p.format = format;
            p.far_near_ratio = ratio;
            p.angle_deg = kOnsetAngleDeg;
            p.separation = 0.1;
            return with_depth_mapping(make_decal_scene(p).scene, mapping, p.far_plane / ratio, p.far_plane);
          },
          true);
  for (DepthFormat format : sweep_depth_formats())
    for (const NamedMethod& method : pseudo_depth_methods()) {
      const double far_distance = cpu::classic::pseudo_depth_far(method.second.methods[0].name);
      // Separations from a tenth of the pair's distance down to 10^-6, largest (benign) first.
      const int top = int(std::floor(4 * std::log10(0.08 * far_distance)));
      add_series(plan, "pseudo_depth", to_string(format), {method}, powers(top, -24, quick ? 2 : 1, 4),
                 [far_distance, format](double s) { return make_decal_scene(pseudo_depth_pair(far_distance, format, s)).scene; },
                 true);
    }
  for (DepthFormat format : sweep_depth_formats())
    add_series(plan, "coplanar_offset", to_string(format), methods,
               pick(quick, {8, 2, 1, 0}, {16, 8, 4, 2, 1.5, 1, 0.5, 0.25, 0}),
               [format](double constant) {
                 PairParams p;
                 p.kind = PairKind::Coplanar;
                 p.format = format;
                 p.far_near_ratio = 1000;
                 p.angle_deg = kOnsetAngleDeg;
                 p.decal_bias = {true, float(-constant), 0, 0};
                 return make_decal_scene(p).scene;
               },
               true);
}

void add_visibility(std::vector<StabilityPoint>& plan, bool quick) {
  const std::vector<NamedMethod> methods = named({{"visibility", "painter"}, {"visibility", "bsp"}});
  add_series(plan, "visibility_cyclic", "three_bars", methods,
             pick(quick, {0, 0.05, 0.1, 0.15, 0.3}, {0, 0.025, 0.05, 0.075, 0.09, 0.1, 0.11, 0.125, 0.15, 0.2, 0.3}),
             make_cyclic_bars);
  add_series(plan, "visibility_interpenetration", "two_squares", methods,
             pick(quick, {0, 0.04, 0.06, 0.1}, {0, 0.02, 0.04, 0.05, 0.052, 0.054, 0.06, 0.08, 0.1, 0.15}),
             make_interpenetration);
}

const std::vector<NamedMethod>& line_methods() {
  static const std::vector<NamedMethod> methods = named({{"line", "dda"}, {"line", "bresenham"}});
  return methods;
}

// The two line modes of a 1-pixel line that the exact path models sample by sample (Default draws
// as rectangular; RectangularSmooth's coverage is an alpha).
constexpr std::pair<const char*, LineMode> kLineModes[] = {{"bresenham", LineMode::Bresenham},
                                                           {"rectangular", LineMode::Rectangular}};

void add_line(std::vector<StabilityPoint>& plan, bool quick) {
  std::vector<double> angles;
  for (int a = 0; a <= 90; a += quick ? 15 : 5) angles.push_back(a);
  const std::vector<double> offsets =  // sub-pixels
      pick(quick, {0, 4, 10, 12, 64, 128}, {0, 1, 2, 4, 8, 10, 11, 12, 16, 32, 64, 96, 128});
  const std::vector<double> lengths =
      pick(quick, {1, 2, 4, 16, 64, 256}, {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256});
  for (const auto& [name, mode] : kLineModes) {
    const LineMode m = mode;
    add_series(plan, "line_slope", name, line_methods(), angles, [m](double a) { return make_line_slope(m, a); });
    add_series(plan, "line_end_offset", name, line_methods(), offsets,
               [m](double d) { return make_line_end_offset(m, d / 256); });
    add_series(plan, "line_length", name, line_methods(), lengths, [m](double l) { return make_line_length(m, l); });
  }
}

void add_cull(std::vector<StabilityPoint>& plan, bool quick) {
  const std::vector<NamedMethod> methods = named({{"cull", "normal_dot_view"}});
  for (const auto& [name, place] : kCullPlaces) {
    // Every 4 degrees from 80 to 100, and closing in on the edge-on angle from both sides.
    const double edge = cull_edge_on_deg(place);
    std::vector<double> angles = quick ? std::vector<double>{80, 88} : std::vector<double>{80, 84, 88};
    for (double d : quick ? std::vector<double>{-0.01, 0, 0.01} : std::vector<double>{-1, -0.1, -0.01, 0, 0.01, 0.1, 1})
      angles.push_back(edge + d);
    for (double a : quick ? std::vector<double>{92, 100} : std::vector<double>{92, 96, 100}) angles.push_back(a);
    std::sort(angles.begin(), angles.end());
    angles.erase(std::unique(angles.begin(), angles.end()), angles.end());
    const CullPlace p = place;
    add_series(plan, "cull_edge_on", name, methods, angles, [p](double a) { return make_cull_face(p, a); });
  }
}

}  // namespace

const std::vector<MapExperiment>& method_map_experiments() { return kExperiments; }

const MapExperiment* find_map_experiment(std::string_view name) {
  for (const MapExperiment& e : kExperiments)
    if (e.name == name) return &e;
  return nullptr;
}

std::vector<NamedMethod> fill_methods() {
  return named({{"fill", "scanline"}, {"fill", "even_odd"}, {"fill", "winding"}, {"fill", "float_edge"},
                {"fill", "flood"}, {"snap", "round_half_away"}, {"tie_break", "none"}});
}

std::vector<NamedMethod> family_methods(std::string_view family) {
  if (family == "fill") return fill_methods();
  if (family == "clip") {
    std::vector<NamedMethod> out = named({{"clip", "sutherland_hodgman"}, {"clip", "weiler_atherton"}});
    for (NamedMethod& m : line_clip_methods())
      if (m.first != "exact") out.push_back(m);
    return out;
  }
  if (family == "depth") {
    std::vector<NamedMethod> out = named({{"depth", "no_fma"}, {"depth", "bilinear"}, {"depth", "perspective_correct"}});
    for (NamedMethod& m : pseudo_depth_methods()) out.push_back(m);
    return out;
  }
  if (family == "visibility") return named({{"visibility", "painter"}, {"visibility", "bsp"}});
  if (family == "line") return line_methods();
  if (family == "cull") return named({{"cull", "normal_dot_view"}});
  return {};
}

PairParams pseudo_depth_pair(double far_distance, DepthFormat format, double separation) {
  PairParams p;
  p.kind = PairKind::NearCoplanar;
  p.format = format;
  p.angle_deg = kOnsetAngleDeg;
  p.separation = separation;
  p.distance = 0.8 * far_distance;
  p.scale = p.distance / 50;
  p.far_plane = 1.2 * far_distance;  // the camera's planes only clip; pseudo-depth takes its own
  p.far_near_ratio = p.far_plane / 20;
  return p;
}

void add_method_maps(std::vector<StabilityPoint>& plan, bool quick) {
  add_fill(plan, quick);
  add_clip(plan, quick);
  add_depth(plan, quick);
  add_visibility(plan, quick);
  add_line(plan, quick);
  add_cull(plan, quick);
}

}  // namespace rastercmp::experiments
