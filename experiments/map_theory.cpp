#include "experiments/map_theory.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <numbers>
#include <utility>

#include <fmt/core.h>

#include "experiments/coverage_model.hpp"
#include "experiments/method_map_scenes.hpp"
#include "experiments/method_maps.hpp"
#include "experiments/scene_make.hpp"
#include "experiments/sweep_common.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {
namespace {

PointTheory clean(const PointFacts&) { return {Outcome::Clean}; }

MapExpectation expectation(std::string expected, std::string legend, std::function<PointTheory(const PointFacts&)> at) {
  return MapExpectation{std::move(expected), std::move(legend), std::move(at), NAN, ""};
}
PointTheory differs_where_drawn(const PointFacts& f) { return {f.drawn ? Outcome::Differs : Outcome::Clean}; }

// ---- fill: the coverage model (coverage_model.hpp) on each map's design triangles -------------

std::optional<CoverageRule> fill_rule(const std::string& method) {
  if (method == "fill=scanline" || method == "fill=even_odd" || method == "fill=winding")
    return CoverageRule{ModelVertices::Real, ModelTies::TopLeft};
  if (method == "fill=float_edge") return CoverageRule{ModelVertices::Real, ModelTies::All};
  if (method == "snap=round_half_away") return CoverageRule{ModelVertices::SnapHalfAway, ModelTies::TopLeft};
  if (method == "tie_break=none") return CoverageRule{ModelVertices::SnapHalfEven, ModelTies::None};
  return std::nullopt;
}

DesignTriangles (*fill_design(const std::string& experiment))(double) {
  if (experiment == "fill_sliver_width") return sliver_strip_design;
  if (experiment == "fill_fan") return fan_design;
  if (experiment == "fill_distance") return far_triangle_design;
  return nullptr;
}

std::optional<MapExpectation> fill_expectation(const std::string& experiment, const std::string& method) {
  const auto design = fill_design(experiment);
  if (design == nullptr) return std::nullopt;
  if (method == "fill=flood") {
    if (experiment == "fill_fan")
      return expectation("differs wherever drawn: each triangle's Bresenham outline is filled whole, so its pixels "
                            "on the spokes take samples the neighbouring triangle owns",
                         "differs where drawn", differs_where_drawn);
    // One triangle: the outline encloses every sample inside the triangle and adds its own pixels,
    // whose centres may lie outside; which ones depends on each edge's lattice phase, so theory
    // gives the direction of the difference, not its size.
    return expectation(
        "adds samples and never loses one: the outline's pixels are filled whole and enclose every sample inside the "
        "triangle, so the samples that differ are the flood fill's count minus the reference's",
        "adds, never loses", [](const PointFacts& f) {
          const double extra = f.method_samples - f.reference_samples;
          return PointTheory{extra > 0 ? Outcome::Differs : Outcome::Clean, extra};
        });
  }
  const auto rule = fill_rule(method);
  if (!rule) return std::nullopt;
  return expectation(
      "the coverage model (experiments/coverage_model.hpp): Vulkan's edge functions on the design vertices, "
      "real for the float methods and snapped to 1/256 for the exact path, with each method's tie rule; "
      "it predicts the count of samples whose owner differs at every point",
      "coverage model", [design, rule = *rule](const PointFacts& f) {
        const double n = double(model_mismatch(design(f.param), rule));
        return PointTheory{n > 0 ? Outcome::Differs : Outcome::Clean, n};
      });
}

// ---- clip -----------------------------------------------------------------------------------
// The clip maps' near vertex is (0.2, 0.6, 0, w) in clip space (make_near_w_triangle,
// make_near_w_line); the cut vertex of clip_near_cross is (0.2, 0.6, -behind, 1). The 64 x 64
// frame puts the near vertex at window y = 32 + 32 * 0.6 / w.

// Coverage never differs; the depth of a vertex the clipper makes may differ in its last float bit
// (a double lerp against lavapipe's float LINTERP, lavapipe-rules §1.6), which no closed form
// places: outcome open, coverage mismatch 0.
PointTheory same_coverage(const PointFacts&) { return {Outcome::Either, 0}; }

// The 2-D clippers need a window position: render_classic refuses a vertex with !(w > 0) or, with
// depth clip on, !(0 <= z <= w) (method_registry needs_2d_clip), under DAZ, so a w below FLT_MIN
// reads as 0.
bool refused_2d_w(double w) { return !(std::fabs(double(float(w))) >= double(FLT_MIN) && w > 0); }
bool refused_2d_behind(double behind) { return std::fabs(double(float(behind))) >= double(FLT_MIN); }

// Past window |y| >= 2^59 a double's step is 128: the frame's 64 and the inner vertex's 12.8 are
// absorbed, Weiler-Atherton finds the corner edge degenerate (and refuses), Cohen-Sutherland's
// intersection x = q.x + (p.x - q.x) (64 - q.y) / (p.y - q.y) cancels to 0 and draws a different line.
// From |y| >= 2^53 its error reaches half a pixel: between the two, pixels may or may not change.
double near_window_y(double w) { return 32 + 32 * 0.6 / double(float(w)); }

// From Mesa 23.2 lavapipe clips lines against z and w only (lavapipe-rules §8.2): the reference
// draws the line whole from its window coordinates, and where the far end's passes 32768 px (an
// edge of 2^23 fixed units) or has none (w <= 0) the integer set-up wraps (§7.5) and its quad is
// not the line, while every classic clipper draws the line clipped to the frame.
bool reference_line_leaves_the_setup(double w) {
  return exact_cpu_options().lavapipe->rules().has(LavapipeRule::LineGuardBand) &&
         (!(double(float(w)) > 0) || near_window_y(w) >= 32768);
}

// The clippers' own rules on clip_near_w, clip_near_w_line and clip_near_cross.
std::optional<MapExpectation> clip_rules(const std::string& experiment, const std::string& method) {
  const bool two_d = method == "clip=weiler_atherton" || method == "clip=cohen_sutherland" || method == "clip=cyrus_beck";
  if (!two_d) {
    if (method != "clip=sutherland_hodgman" && method != "clip=cohen_sutherland_3d" && method != "clip=liang_barsky")
      return std::nullopt;
    return expectation("no sample's coverage differs: the method clips in homogeneous coordinates, as the exact path; "
                       "the depth of a vertex it makes may differ in the last float bit (open)",
                       "coverage never differs", same_coverage);
  }
  if (experiment == "clip_near_cross")
    return expectation("refused wherever the vertex lies behind the near plane (float(-behind) < 0): the method "
                       "clips x and y in window space only and needs 0 <= z <= w; elsewhere coverage never differs",
                       "refused behind the near plane", [](const PointFacts& f) {
                         return refused_2d_behind(f.param) ? PointTheory{Outcome::Refused} : same_coverage(f);
                       });
  if (method == "clip=weiler_atherton")
    return expectation("refused where float(w) < FLT_MIN (no window position) and where the near vertex's window y "
                       "reaches 2^59, w <= 3.3e-17 (double steps of 128 absorb the frame: a degenerate corner "
                       "edge); elsewhere coverage never differs",
                       "refused from w = 3.3e-17", [](const PointFacts& f) {
                         return refused_2d_w(f.param) || near_window_y(f.param) >= 0x1p59 ? PointTheory{Outcome::Refused}
                                                                                            : same_coverage(f);
                       });
  if (method == "clip=cohen_sutherland")
    return expectation("refused where float(w) < FLT_MIN; differs where the near vertex's window y reaches 2^59 "
                       "(w <= 3.3e-17: the intersection's x cancels to 0); open from 2^53 (w <= 2.1e-15), where its "
                       "error passes half a pixel; elsewhere coverage never differs",
                       "differs from w = 3.3e-17", [](const PointFacts& f) {
                         if (refused_2d_w(f.param)) return PointTheory{Outcome::Refused};
                         const double y = near_window_y(f.param);
                         if (y >= 0x1p59) return PointTheory{Outcome::Differs};
                         if (y >= 0x1p53) return PointTheory{Outcome::Either};
                         return same_coverage(f);
                       });
  return expectation("refused where float(w) < FLT_MIN; elsewhere coverage never differs (t from a small exact "
                     "numerator, the end within 2^-53 of its place)",
                     "refused below FLT_MIN", [](const PointFacts& f) {
                       return refused_2d_w(f.param) ? PointTheory{Outcome::Refused} : same_coverage(f);
                     });
}

// The clippers' rules, and on clip_near_w_line, where the release does not clip lines in x and y,
// a difference wherever the reference's line leaves the set-up's range (the method's own refusal
// first).
std::optional<MapExpectation> clip_expectation(const std::string& experiment, const std::string& method) {
  std::optional<MapExpectation> base = clip_rules(experiment, method);
  if (!base || experiment != "clip_near_w_line") return base;
  if (!exact_cpu_options().lavapipe->rules().has(LavapipeRule::LineGuardBand)) return base;
  return expectation(base->expected + "; and, lines not clipped in x and y by this release (lavapipe-rules §8.2), "
                                      "differs wherever the reference's line reaches 32768 px or w <= 0, where its "
                                      "set-up wraps",
                     base->legend + ", wraps from w = 5.9e-4",
                     [at = base->at](const PointFacts& f) {
                       const PointTheory own = at(f);
                       if (own.outcome == Outcome::Refused || !reference_line_leaves_the_setup(f.param)) return own;
                       return PointTheory{Outcome::Differs};
                     });
}

// ---- line -----------------------------------------------------------------------------------
// Both ends at pixel centres, a whole-pixel run: M the major and m the minor extent, g = gcd,
// M' = M / g. The real line passes exactly half-way between two centres of a column iff M' is
// even (at column M / 2). The classic algorithms draw the nearest centre of each major column;
// Vulkan's Bresenham lines (diamond exit) the same except at such a tie, where each rule picks its
// own side (lavapipe's pick also depends on its end pull-back, which changed between releases), so
// theory leaves a tie open. A rectangular line covers every centre within 1/2 across the line:
// per column the second-nearest centre lies max(r, 1 - r) away along the minor axis, at least
// ceil(M'/2) / M', inside the rectangle's half-height L / (2M) (L the length) iff g ceil(M'/2) < L/2
// — and with the half-width's normal snapped to 1/256 (lavapipe-rules §4) L/2 becomes
// H = (M round(128 M / L) + m round(128 m / L)) / 256, a tie column also counting when M / 2 > H.
struct LineRun {
  int64_t major = 0, minor = 0;
};

LineRun line_run(glm::dvec2 run) {
  const int64_t x = std::llabs(std::llround(run.x)), y = std::llabs(std::llround(run.y));
  return {std::max(x, y), std::min(x, y)};
}

bool has_tie(LineRun r) { return r.minor > 0 && r.minor < r.major && (r.major / std::gcd(r.major, r.minor)) % 2 == 0; }

bool rectangle_adds(LineRun r) {
  if (r.minor == 0 || r.minor == r.major) return false;
  const int64_t g = std::gcd(r.major, r.minor), reduced = r.major / g;
  const double length = std::hypot(double(r.major), double(r.minor));
  const double half = (double(r.major) * std::round(128 * r.major / length) +
                       double(r.minor) * std::round(128 * r.minor / length)) / 256;
  return double(g * ((reduced + 1) / 2)) < half || (reduced % 2 == 0 && double(r.major) / 2 > half);
}

std::optional<MapExpectation> line_expectation(const std::string& experiment, const std::string& case_name,
                                               const std::string& method) {
  if (method != "line=dda" && method != "line=bresenham") return std::nullopt;
  glm::dvec2 (*run)(double) = experiment == "line_slope"    ? line_slope_run
                              : experiment == "line_length" ? line_length_run
                                                            : nullptr;
  if (run == nullptr) {
    if (experiment != "line_end_offset" || case_name != "rectangular") return std::nullopt;
    return expectation("no closed form: with the end off its centre, the rectangle's count is a lattice count in a "
                       "thin rotated rectangle, which gains or loses a centre wherever one crosses its sides; the "
                       "classic line stays the same until the end changes pixel",
                       "open (no closed form)", [](const PointFacts&) { return PointTheory{Outcome::Either}; });
  }
  if (case_name == "bresenham")
    return expectation("differs from the diamond-exit line only at a tie: a column half-way between two centres, "
                       "iff M / gcd(M, m) is even; each rule picks its own side there, so theory leaves it open",
                       "open at ties, else clean", [run](const PointFacts& f) {
                         return PointTheory{has_tie(line_run(run(f.param))) ? Outcome::Either : Outcome::Clean};
                       });
  if (case_name == "rectangular")
    return expectation("differs iff the rectangle holds a second centre of some column: g ceil(M'/2) < H or a tie "
                       "with M / 2 > H, H the snapped half-height (map_theory.cpp)",
                       "second centre in a column", [run](const PointFacts& f) {
                         return PointTheory{rectangle_adds(line_run(run(f.param))) ? Outcome::Differs : Outcome::Clean};
                       });
  return std::nullopt;
}

// ---- depth and visibility: the series without a predicted boundary -------------------------

std::optional<MapExpectation> depth_expectation(const std::string& experiment, const std::string& case_name,
                                                const std::string& method) {
  if (experiment != "depth_far_near") return std::nullopt;
  if (method == "depth=perspective_correct")
    return expectation(
        "the wrong surface wins at every far/near: window z is affine in 1/w (A + B/w, B < 0; reversed C/w - D, "
        "C > 0), and weighting it by 1/w puts sum(l/w^2) / sum(l/w) >= sum(l/w) (Cauchy-Schwarz) in place of 1/w, "
        "so every triangle is drawn nearer than its plane, the more so the wider its spread of w; the base's "
        "triangles spread more than the decal's and come out in front",
        "wrong at every point", [](const PointFacts&) { return PointTheory{Outcome::Differs}; });
  const bool interpolates_the_plane = method == "exact" || method == "depth=no_fma" || method == "depth=bilinear";
  if (interpolates_the_plane && case_name.rfind("d32_sfloat_reversed", 0) == 0)
    return expectation("never fights up to far/near 10^6: reversed D32 stores z ~ n / w, whose float step is "
                       "relative (2^-24 z), so the pair's gap n dz / w^2 stays about 2^24 dz / w steps",
                       "no fight", clean);
  return std::nullopt;
}

std::optional<MapExpectation> visibility_expectation(const std::string& method) {
  if (method != "visibility=bsp") return std::nullopt;
  return expectation("no sample differs: the BSP tree splits every polygon its partition planes cross, so cyclic "
                     "overlap and interpenetration are drawn back to front piece by piece, as the z-buffer sees them",
                     "no difference", clean);
}

// ---- cull ---------------------------------------------------------------------------------------

std::optional<MapExpectation> cull_expectation(const std::string& case_name, const std::string& method) {
  if (method != "cull=normal_dot_view") return std::nullopt;
  for (const auto& [name, place] : kCullPlaces) {
    if (case_name != name) continue;
    const double edge = cull_edge_on_deg(place);
    if (place == CullPlace::YFlip)
      return MapExpectation{"differs wherever either draws the face: the negative viewport height reverses the "
                            "window winding, which N.V in clip space cannot see",
                            "differs where drawn", differs_where_drawn, edge, "edge-on to the eye"};
    // Snapping moves a vertex by up to 1/512 px: it can flip the sign of a face F px across only
    // within about 1 / (256 F) radians of edge-on.
    const double band = 180 / std::numbers::pi / (256 * cull_face_pixels());
    return MapExpectation{fmt::format("no sample differs: N.V with V from the eye has the sign of the projected "
                                      "area, so both switch at {:g} degrees (a view-axis V would switch at 90); "
                                      "snapping could part them only within about {:.2g} degrees of it, where the "
                                      "face covers no sample",
                                      edge, band),
                          "no difference", clean, edge, "edge-on to the eye"};
  }
  return std::nullopt;
}

Outcome measured_outcome(double value, double threshold, bool refused) {
  if (refused) return Outcome::Refused;
  return value > threshold ? Outcome::Differs : Outcome::Clean;
}

}  // namespace

const char* to_string(Outcome outcome) {
  switch (outcome) {
    case Outcome::Clean: return "clean";
    case Outcome::Differs: return "differs";
    case Outcome::Refused: return "refused";
    case Outcome::Either: return "either";
  }
  return "?";
}

std::optional<BoundaryPrediction> method_map_prediction(const std::string& experiment, const std::string& case_name,
                                                        const std::string& method) {
  if (experiment == "line_end_offset" && case_name == "bresenham" &&
      (method == "line=dda" || method == "line=bresenham")) {
    double smallest = INFINITY;
    for (int k = 1; k < kLineOffsetRun; ++k) {
      const double y = double(kLineOffsetRise) * k / kLineOffsetRun;
      smallest = std::min(smallest, (std::round(y) + 0.5 - y) * kLineOffsetRun / k);
    }
    return BoundaryPrediction{256 * smallest,
                              "smallest end offset d (sub-pixels) at which the real line crosses half "
                              "a pixel at a column k between the ends: 256 min_k (round(y_k) + 0.5 - "
                              "y_k) 41 / k, y_k = 13 k / 41"};
  }
  return std::nullopt;
}

std::optional<MapExpectation> method_map_expectation(const std::string& experiment, const std::string& case_name,
                                                     const std::string& method) {
  const MapExperiment* e = find_map_experiment(experiment);
  if (e == nullptr) return std::nullopt;
  if (e->family == "depth") return depth_expectation(experiment, case_name, method);  // else predicted boundaries
  if (e->family == "visibility" && method != "exact") return visibility_expectation(method);
  if (method == "exact") {
    // Mesa 26.2 reworked the wrapping integer set-up, which the profile does not model (lavapipe-rules
    // §8.7): where the reference's unclipped line leaves the set-up's range the exact path refuses.
    if (experiment == "clip_near_w_line" &&
        exact_cpu_options().lavapipe->rules().has(LavapipeRule::RasterizerOverflowReworked))
      return expectation("no sample differs: the exact path is lavapipe's model (docs/lavapipe-rules.md); where the "
                         "line leaves the set-up's range it may refuse, this release's wrapping not being modelled "
                         "(§8.7)",
                         "no difference, open past the set-up's range", [](const PointFacts& f) {
                           return PointTheory{reference_line_leaves_the_setup(f.param) ? Outcome::Either
                                                                                        : Outcome::Clean};
                         });
    return expectation("no sample differs: the exact path is lavapipe's model (docs/lavapipe-rules.md)",
                       "no difference", clean);
  }
  if (e->family == "fill") return fill_expectation(experiment, method);
  if (e->family == "cull") return cull_expectation(case_name, method);
  if (e->family == "clip") return clip_expectation(experiment, method);
  if (e->family == "line") return line_expectation(experiment, case_name, method);
  return std::nullopt;
}

std::vector<PointCheck> check_expectation(const CsvTable& table, const FailureBoundary& b,
                                          const MapExpectation& expected) {
  const MapExperiment* e = find_map_experiment(b.experiment);
  const std::string measure = e ? std::string(e->measure) : "any_mismatch";
  const size_t param = table.column("param_a"), agree = table.column("cpu_vk_agree"),
               cpu = table.column("value_cpu"), vk = table.column("value_vk"),
               coverage = table.column("coverage_mismatch");
  std::vector<PointCheck> out;
  double threshold = measure == "excess_mismatch" ? NAN : 0;
  for (const Row& row :
       select_rows(table, {{"experiment", b.experiment}, {"case", b.case_name}, {"method", b.method}})) {
    const bool refused = row[agree] == "not_supported";
    const double value = map_measure(table, row, measure);
    if (!refused && std::isnan(threshold)) threshold = value;  // excess_mismatch: the benign end's own value
    PointFacts facts{to_double(row[param]), to_double(row[cpu]) > 0 || to_double(row[vk]) > 0, to_double(row[cpu]),
                     to_double(row[vk])};
    PointCheck c{facts.param, expected.at(facts), measured_outcome(value, threshold, refused),
                 to_double(row[coverage]), false};
    const bool outcome_agrees = c.predicted.outcome == c.measured || c.predicted.outcome == Outcome::Either;
    c.agrees = outcome_agrees &&
               (std::isnan(c.predicted.coverage_mismatch) || c.predicted.coverage_mismatch == c.measured_coverage_mismatch);
    out.push_back(c);
  }
  return out;
}

bool expectation_holds(const CsvTable& table, const FailureBoundary& b, const MapExpectation& expected) {
  const std::vector<PointCheck> points = check_expectation(table, b, expected);
  return !points.empty() && std::all_of(points.begin(), points.end(), [](const PointCheck& c) { return c.agrees; });
}

}  // namespace rastercmp::experiments
