#include "cpu_raster/spec/depth_gate.hpp"

#include "cpu_raster/spec/line_coverage.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "model/depth_format.hpp"

namespace rastercmp::cpu::spec {
namespace {

// Pixels past a line's ends and sides that a device may still cover (line_coverage.hpp margin).
constexpr double kLineReachMarginPx = 1.0;

struct Interval {
  double lo = 0, hi = 0;
};

// One step of a UNORM format; 0 for float depth.
double unorm_step(DepthFormat format) { return depth_format_info(format).mrd; }

// Largest r: UNORM 2/(2^n - 1) (lavapipe, docs/lavapipe-rules.md §4.3); D32 2^(e-23) with e <= 0 for
// depths up to 1, doubled for slack.
double r_max(DepthFormat format) {
  const DepthFormatInfo info = depth_format_info(format);
  return info.encoding == DepthEncoding::Float ? 2.0 * float_depth_r(info, 1.0) : 2.0 * unorm_step(format);
}

// dbclamp of the offset interval (Vulkan "Depth Bias Computation").
Interval bias_interval(const DepthBias& bias, DepthFormat format, double slope, bool optional) {
  Interval o;
  if (bias.enable && (bias.constant_factor != 0 || bias.slope_factor != 0)) {
    const double reach =
        std::fabs(double(bias.constant_factor)) * r_max(format) + std::fabs(double(bias.slope_factor)) * slope;
    o = {-reach, reach};
    const double clamp = bias.clamp;
    if (clamp > 0) o = {std::min(o.lo, clamp), std::min(o.hi, clamp)};
    if (clamp < 0) o = {std::max(o.lo, clamp), std::max(o.hi, clamp)};
  }
  if (optional) o = {std::min(o.lo, 0.0), std::max(o.hi, 0.0)};
  return o;
}

// The plane through the primitive's window vertices; false when it has none (a flat triangle or
// a zero-length line whose vertex depths differ).
bool fit_plane(const DepthPrimitive& p, DepthJudge& j) {
  const glm::dvec3 a = p.vertices[0];
  j.x0 = a.x;
  j.y0 = a.y;
  j.z0 = a.z;
  const bool constant =
      std::all_of(p.vertices.begin(), p.vertices.end(), [&](const glm::dvec3& v) { return v.z == a.z; });
  if (p.vertices.size() == 2) {
    const glm::dvec3 d = p.vertices[1] - a;
    const double length2 = d.x * d.x + d.y * d.y;
    if (length2 == 0) return constant;
    j.dzdx = d.z * d.x / length2;  // z along the segment: t = (p - a)·d / |d|^2
    j.dzdy = d.z * d.y / length2;
    return true;
  }
  const glm::dvec3 u = p.vertices[1] - a, v = p.vertices[2] - a;
  const double det = u.x * v.y - v.x * u.y;
  if (det == 0) return constant;
  j.dzdx = (u.z * v.y - v.z * u.y) / det;
  j.dzdy = (u.x * v.z - v.x * u.z) / det;
  return true;
}

enum class Outcome { Pass, Fail, Unknown };

// The test "fragment op clear" for every fragment depth in z (Vulkan "Depth Comparison").
Outcome compare_with_clear(CompareOp op, const Interval& z, double clear) {
  const auto decide = [](bool pass, bool fail) {
    return pass ? Outcome::Pass : fail ? Outcome::Fail : Outcome::Unknown;
  };
  switch (op) {
    case CompareOp::Always: return Outcome::Pass;
    case CompareOp::Never: return Outcome::Fail;
    case CompareOp::Less: return decide(z.hi < clear, z.lo >= clear);
    case CompareOp::LessOrEqual: return decide(z.hi <= clear, z.lo > clear);
    case CompareOp::Greater: return decide(z.lo > clear, z.hi <= clear);
    case CompareOp::GreaterOrEqual: return decide(z.lo >= clear, z.hi < clear);
    case CompareOp::Equal: return decide(false, z.hi < clear || z.lo > clear);
    case CompareOp::NotEqual: return decide(z.hi < clear || z.lo > clear, false);
  }
  return Outcome::Unknown;
}

// The slope m of "Depth Bias Computation" over every placement of the device's vertices: each
// vertex anywhere in a square of half-size `move_px` around its window position and its z within
// `move_z`; m between max(|dz/dx|, |dz/dy|) (the allowed approximation) and the exact
// sqrt(dz/dx^2 + dz/dy^2). Gradients are not multilinear in the positions, so the corners are a
// sample of the placements; unbounded when some placement flips or flattens the triangle.
struct SlopeRange {
  double lo = 0, hi = 0;
  bool bounded = true;
};

SlopeRange triangle_slope_range(const DepthPrimitive& p, double move_px, double move_z) {
  SlopeRange m{std::numeric_limits<double>::infinity(), 0.0, true};
  const auto det_of = [](const std::array<glm::dvec3, 3>& t) {
    return (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y);
  };
  const std::array<glm::dvec3, 3> exact{p.vertices[0], p.vertices[1], p.vertices[2]};
  const double sign = det_of(exact) > 0 ? 1.0 : -1.0;
  for (uint32_t combo = 0; combo < (1u << 9); ++combo) {
    std::array<glm::dvec3, 3> t = exact;
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t bits = combo >> (3 * k);
      t[k].x += (bits & 1u) ? move_px : -move_px;
      t[k].y += (bits & 2u) ? move_px : -move_px;
      t[k].z += (bits & 4u) ? move_z : -move_z;
    }
    const double det = det_of(t);
    if (!(det * sign > 0)) return SlopeRange{0, 0, false};
    const glm::dvec3 u = t[1] - t[0], w = t[2] - t[0];
    const double gx = (u.z * w.y - w.z * u.y) / det, gy = (u.x * w.z - w.x * u.z) / det;
    m.lo = std::min(m.lo, std::max(std::fabs(gx), std::fabs(gy)));
    m.hi = std::max(m.hi, std::hypot(gx, gy));
  }
  return m;
}

// r of "Depth Bias Computation" over what the spec allows. Fixed point: "implementation-dependent
// but must be at most r = 2 x 2^-n", and not below 2^-n, the value it must be when the
// implementation may not scale it (depthBiasExact); lavapipe's 2/(2^n - 1) is the upper end.
// Floating point: r = 2^(e-n), e the largest exponent of the primitive's z values, taken over the
// clipped piece and the primitive before clipping, times up to 2 (without depthBiasExact the
// implementation may "scale the depth bias value to ensure a minimum resolvable distance"); 0 at
// the low end for z values below 2^-100, where lavapipe's r underflows to 0.
Interval r_range(DepthFormat format, double piece_max_abs_z, double source_max_abs_z) {
  const DepthFormatInfo info = depth_format_info(format);
  if (info.encoding == DepthEncoding::Unorm) return {std::ldexp(1.0, -int(info.bits)), 2.0 * info.mrd};
  const double lo = piece_max_abs_z < std::ldexp(1.0, -100) ? 0.0 : float_depth_r(info, piece_max_abs_z);
  return {lo, 2.0 * float_depth_r(info, std::max(piece_max_abs_z, source_max_abs_z))};
}

// What the depth intervals need beyond the gate: vertex range, bias over every r and m, precision.
void set_interval_terms(const Scene& scene, const RasterState& state, const DepthPrimitive& p, DepthJudge& j) {
  constexpr double eps = kSpecRelativeAccuracy;
  const bool is_line = p.vertices.size() == 2;
  j.format = scene.depth_format;
  j.line = is_line;
  j.writes = state.depth.test_enable && state.depth.write_enable && state.depth.compare_op != CompareOp::Never;
  const Viewport v = scene.effective_viewport();
  const double o_z = std::fabs(double(v.min_depth)), p_z = std::fabs(double(v.max_depth) - double(v.min_depth));
  const double o_xy = std::max(std::fabs(double(v.x) + 0.5 * v.width), std::fabs(double(v.y) + 0.5 * v.height));
  double max_abs_z = 0;
  j.vertex_lo = j.vertex_hi = p.vertices[0].z;
  for (const glm::dvec3& vertex : p.vertices) {
    j.vertex_lo = std::min(j.vertex_lo, vertex.z);
    j.vertex_hi = std::max(j.vertex_hi, vertex.z);
    max_abs_z = std::max(max_abs_z, std::fabs(vertex.z));
    j.coord_max = std::max({j.coord_max, std::fabs(vertex.x), std::fabs(vertex.y)});
  }
  // z_f = p_z z_d + o_z with z_d = z_c / w_c: three operations, each accurate to eps.
  j.vertex_error = 3 * eps * (max_abs_z + o_z + p_z) + p.clip_error_z;
  j.reach_precision_px = 3 * eps * (j.coord_max + o_xy) + p.clip_error_px;
  j.reach_px = p.box_half_px + p.snap_px;
  j.interval_reach_px = p.sample_half_px + p.snap_px;  // a single sample lies at the pixel centre
  if (is_line) {
    j.reach_px += 0.5 * std::ceil(widest_line_width(float(p.line_width))) + kLineReachMarginPx;
    j.interval_reach_px = j.reach_px;
  }
  const DepthBias& bias = state.depth_bias;
  if (!j.plane_defined || !bias.enable || (bias.constant_factor == 0 && bias.slope_factor == 0)) return;
  SlopeRange m{0, std::fabs(j.dzdx) + std::fabs(j.dzdy), true};  // lines: m is not defined for them
  if (!is_line && bias.slope_factor != 0) m = triangle_slope_range(p, p.snap_px + j.reach_precision_px, j.vertex_error);
  if (!m.bounded) {
    j.bias_any = true;
    return;
  }
  const Interval r = r_range(scene.depth_format, max_abs_z, std::max(max_abs_z, p.source_max_abs_z));
  const double c = bias.constant_factor, s = bias.slope_factor;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double rv : {r.lo, r.hi})
    for (const double mv : {m.lo * (1 - 4 * eps), m.hi * (1 + 4 * eps)}) {
      const double o = c * rv + s * mv, error = 3 * eps * (std::fabs(c * rv) + std::fabs(s * mv));
      lo = std::min(lo, o - error);
      hi = std::max(hi, o + error);
    }
  j.bias_lo = dbclamp(lo, bias.clamp);
  j.bias_hi = dbclamp(hi, bias.clamp);
  if (is_line) {  // "may also be applied" to lines
    j.bias_lo = std::min(j.bias_lo, 0.0);
    j.bias_hi = std::max(j.bias_hi, 0.0);
  }
}

}  // namespace

double dbclamp(double o, float clamp) {
  if (clamp > 0) return std::min(o, double(clamp));
  if (clamp < 0) return std::max(o, double(clamp));
  return o;  // 0 or NaN
}

DepthJudge make_depth_judge(const Scene& scene, const RasterState& state, const DepthPrimitive& p) {
  DepthJudge j;
  if (!scene.has_depth()) return j;
  const Viewport v = scene.effective_viewport();
  j.clamp = state.depth_clamp;
  j.zmin = std::min(v.min_depth, v.max_depth);
  j.zmax = std::max(v.min_depth, v.max_depth);
  j.plane_defined = fit_plane(p, j);
  set_interval_terms(scene, state, p, j);
  if (!state.depth.test_enable || state.depth.compare_op == CompareOp::Always) return j;
  j.op = state.depth.compare_op;
  j.kind = j.op == CompareOp::Never ? DepthJudge::Kind::Fail : DepthJudge::Kind::Compare;
  if (j.kind == DepthJudge::Kind::Fail) return j;
  j.clear = scene.depth_clear;
  const bool is_line = p.vertices.size() == 2;
  if (!j.plane_defined) {
    j.kind = DepthJudge::Kind::Undefined;
    return j;
  }
  const double slope = std::fabs(j.dzdx) + std::fabs(j.dzdy);
  const Interval offset = bias_interval(state.depth_bias, scene.depth_format, slope, is_line);
  j.offset_lo = offset.lo;
  j.offset_hi = offset.hi;
  double coord_max = 0;
  j.range_lo = j.range_hi = p.vertices[0].z;
  for (const glm::dvec3& vertex : p.vertices) {
    j.range_lo = std::min(j.range_lo, vertex.z);
    j.range_hi = std::max(j.range_hi, vertex.z);
    coord_max = std::max({coord_max, std::fabs(vertex.x), std::fabs(vertex.y)});
  }
  const double past_ends = is_line ? slope * j.reach_px : 0.0;
  j.range_lo += offset.lo - past_ends;
  j.range_hi += offset.hi + past_ends;
  if (!j.clamp && (j.range_lo < j.zmin || j.range_hi > j.zmax)) j.kind = DepthJudge::Kind::Undefined;
  j.slack = kDepthSlack + (slope * coord_max + 1.0) * std::ldexp(1.0, -20);
  j.unorm_step = unorm_step(scene.depth_format);
  return j;
}

Gate depth_gate_at(const DepthJudge& j, glm::dvec2 pos) {
  switch (j.kind) {
    case DepthJudge::Kind::Pass: return Gate::Certain;
    case DepthJudge::Kind::Fail: return Gate::Never;
    case DepthJudge::Kind::Undefined: return Gate::Maybe;
    case DepthJudge::Kind::Compare: break;
  }
  const double z = j.z0 + j.dzdx * (pos.x - j.x0) + j.dzdy * (pos.y - j.y0);
  const double spread = (std::fabs(j.dzdx) + std::fabs(j.dzdy)) * j.reach_px;
  Interval fragment{std::max(z - spread + j.offset_lo, j.range_lo), std::min(z + spread + j.offset_hi, j.range_hi)};
  if (fragment.lo > fragment.hi) return Gate::Maybe;          // no device fragment can be here; stay neutral
  fragment = {fragment.lo - j.slack, fragment.hi + j.slack};  // interpolation error, then the clamp
  if (j.clamp) fragment = {std::clamp(fragment.lo, j.zmin, j.zmax), std::clamp(fragment.hi, j.zmin, j.zmax)};
  if (j.unorm_step > 0) {
    // Fragment and clear value each rounded either way to the UNORM grid, whose ends 0 and 1 are
    // exact: two steps, within [0, 1].
    fragment = {std::max(0.0, fragment.lo - 2 * j.unorm_step), std::min(1.0, fragment.hi + 2 * j.unorm_step)};
  }
  switch (compare_with_clear(j.op, fragment, j.clear)) {
    case Outcome::Pass: return Gate::Certain;
    case Outcome::Fail: return Gate::Never;
    case Outcome::Unknown: return Gate::Maybe;
  }
  return Gate::Maybe;
}

namespace {

// The widening of one end of a range and the term it came from; the largest one names the end.
struct Widening {
  double amount = 0;
  DepthTerm term = DepthTerm::Plane;
};

Widening largest(std::initializer_list<Widening> candidates) {
  Widening best;
  for (const Widening& w : candidates)
    if (w.amount > best.amount) best = w;
  return best;
}

}  // namespace

DepthValueRange fragment_depth_range(const DepthJudge& j, glm::dvec2 pos) {
  DepthValueRange out;
  if (!j.plane_defined || j.bias_any) {
    out.any = true;
    out.lo_term = out.hi_term = j.plane_defined ? DepthTerm::Bias : DepthTerm::Undefined;
    return out;
  }
  constexpr double eps = kSpecRelativeAccuracy;
  const double slope = std::fabs(j.dzdx) + std::fabs(j.dzdy);
  const double reach = j.interval_reach_px + j.reach_precision_px;
  const double z = j.z0 + j.dzdx * (pos.x - j.x0) + j.dzdy * (pos.y - j.y0);
  // Triangles: a convex combination of the vertex depths ("Basic Polygon Rasterization").
  // Lines: a device's fragment may project past an end (line_coverage.hpp margin).
  const double past_ends = j.line ? slope * reach : 0.0;
  const double range_lo = j.vertex_lo - past_ends, range_hi = j.vertex_hi + past_ends;
  const double centre = std::clamp(z, range_lo, range_hi);
  const double plane_lo = std::max(z - slope * reach, range_lo), plane_hi = std::min(z + slope * reach, range_hi);
  const double lo0 = std::min(plane_lo, centre), hi0 = std::max(plane_hi, centre);
  double lo = lo0 + j.bias_lo, hi = hi0 + j.bias_hi;
  // "If z_f is not in the range [z_min, z_max], then z_f is undefined following this step."
  if (!j.clamp && (lo < j.zmin || hi > j.zmax)) {
    out.any = true;
    out.lo_term = out.hi_term = DepthTerm::Undefined;
    return out;
  }
  // Plus an absolute 2^-126 per operation: a denormal result may be flushed to zero (the SPIR-V
  // precision rules allow it in shaders; the viewport's depth has no stricter rule).
  const double precision = j.vertex_error + 4 * eps * (std::fabs(z) + slope * j.coord_max) +
                           eps * std::max(std::fabs(lo), std::fabs(hi)) + 8 * std::ldexp(1.0, -126);
  const Widening lo_term = largest({{centre - lo0, DepthTerm::Snapping},
                                    {std::fabs(j.bias_lo), DepthTerm::Bias},
                                    {precision, DepthTerm::Precision}});
  const Widening hi_term = largest({{hi0 - centre, DepthTerm::Snapping},
                                    {std::fabs(j.bias_hi), DepthTerm::Bias},
                                    {precision, DepthTerm::Precision}});
  lo -= precision;
  hi += precision;
  // With depth clamp the value is clamped to the range; without it a value that only the precision
  // allowance puts past the range is taken as clamped too (to [0, 1], lavapipe's clamp).
  const double clamp_lo = j.clamp ? j.zmin : std::min(0.0, j.zmin), clamp_hi = j.clamp ? j.zmax : std::max(1.0, j.zmax);
  out.lo = std::clamp(lo, clamp_lo, clamp_hi);
  out.hi = std::clamp(hi, clamp_lo, clamp_hi);
  out.lo_term = lo_term.term;
  out.hi_term = hi_term.term;
  out.lo_widening = lo_term.amount;
  out.hi_widening = hi_term.amount;
  return out;
}

DepthInterval depth_format_interval(DepthFormat format, const DepthValueRange& range) {
  DepthInterval out;
  out.lo_term = range.lo_term;
  out.hi_term = range.hi_term;
  if (range.any) {
    out.any = true;
    return out;
  }
  const DepthFormatInfo info = depth_format_info(format);
  double step_lo = 0, step_hi = 0;
  if (info.encoding == DepthEncoding::Unorm) {
    // "convertFloatToUint(r, b) returns one of the two unsigned binary integer values with exactly b
    // bits which are closest to the floating-point value r" after clamping f to [0, 1].
    const double max = double(unorm_max(info));
    out.lo_raw = uint32_t(std::floor(std::clamp(range.lo, 0.0, 1.0) * max));
    out.hi_raw = uint32_t(std::ceil(std::clamp(range.hi, 0.0, 1.0) * max));
    step_lo = step_hi = 1.0 / max;
  } else {
    // "finite values falling between two representable finite values are rounded to one or the other"
    float lo = float(range.lo), hi = float(range.hi);
    if (double(lo) > range.lo) lo = std::nextafter(lo, -std::numeric_limits<float>::infinity());
    if (double(hi) < range.hi) hi = std::nextafter(hi, std::numeric_limits<float>::infinity());
    out.lo_raw = std::bit_cast<uint32_t>(lo);
    out.hi_raw = std::bit_cast<uint32_t>(hi);
    step_lo = double(lo) - double(std::nextafter(lo, -std::numeric_limits<float>::infinity()));
    step_hi = double(std::nextafter(hi, std::numeric_limits<float>::infinity())) - double(hi);
  }
  if (step_lo > range.lo_widening) out.lo_term = DepthTerm::Rounding;
  if (step_hi > range.hi_widening) out.hi_term = DepthTerm::Rounding;
  return out;
}

}  // namespace rastercmp::cpu::spec
