#include "cpu_raster/spec/depth_gate.hpp"

#include <algorithm>
#include <cmath>

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

}  // namespace

DepthJudge make_depth_judge(const Scene& scene, const RasterState& state, const DepthPrimitive& p) {
  DepthJudge j;
  if (!scene.has_depth() || !state.depth.test_enable || state.depth.compare_op == CompareOp::Always) return j;
  j.op = state.depth.compare_op;
  j.kind = j.op == CompareOp::Never ? DepthJudge::Kind::Fail : DepthJudge::Kind::Compare;
  if (j.kind == DepthJudge::Kind::Fail) return j;
  j.clear = scene.depth_clear;
  const Viewport v = scene.effective_viewport();
  j.clamp = state.depth_clamp;
  j.zmin = std::min(v.min_depth, v.max_depth);
  j.zmax = std::max(v.min_depth, v.max_depth);
  const bool is_line = p.vertices.size() == 2;
  if (!fit_plane(p, j)) {
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
  j.reach_px = p.box_half_px + p.snap_px;
  if (is_line) j.reach_px += 0.5 * std::ceil(p.line_width) + kLineReachMarginPx;
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

}  // namespace rastercmp::cpu::spec
