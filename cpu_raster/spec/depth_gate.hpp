// Whether a primitive's fragment at a sample it covers is certainly written, certainly not, or
// either. Only the union of all draws is classified, and for that the depth test reduces to one
// comparison: a sample ends up covered iff some fragment there passes the test against the
// CLEARED value. (The depth attachment changes only when a fragment passes, and the owner is
// written whenever one passes, so until the first pass every fragment meets the clear value;
// after it the sample is covered for good.) Vulkan "Depth Comparison" (fragops.adoc).
//
// The fragment depth at a sample is the primitive's plane there (linear interpolation,
// primsrast.adoc), evaluated here in double from the exact window vertices, widened for
//  - where the device samples inside the judged box: slope * box half-size;
//  - the device's own plane through its snapped vertices: at each snapped vertex it differs from
//    this plane by at most slope * (snapping + float slack); a covered sample lies inside the
//    device's snapped triangle, a convex combination of its vertices, so the bound holds there;
//  - lines: half the width plus the line margin, since Bresenham and rectangular lines project a
//    sample onto the segment differently and may reach past its ends;
//  - depth bias: |constant| * r_max + |slope factor| * m, then depthBiasClamp (Vulkan "Depth Bias
//    Computation"; r_max = 2/(2^n - 1) for UNORM, lavapipe's value, above the spec's 2 * 2^-n;
//    m <= |dz/dx| + |dz/dy|); lines may or may not get it ("may also be applied");
//  - float error of the interpolation, before depth clamp: kDepthSlack, plus the error of drivers
//    that, like lavapipe, extrapolate the plane to the framebuffer origin (relative to slope *
//    coordinate size);
//  - after the clamp, the conversion the spec leaves open: two steps of a UNORM format (the
//    fragment and the clear value each rounded either way), whose ends 0 and 1 are exact.
// Without depth clamp a depth outside the viewport's [min(n,f), max(n,f)] is undefined
// (fragops.adoc "Depth Clamping and Range Adjustment", docs/lavapipe-rules.md §1.1), and so is the test
// result. That is judged on the range the exact values can take: a triangle's fragments are convex
// combinations of its vertex depths (plus bias), a line's may extrapolate past its ends; float
// error at the ends of that range is not taken for leaving it.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::spec {

enum class Gate : uint8_t { Never = 0, Maybe = 1, Certain = 2 };

inline Gate weaker(Gate a, Gate b) { return a < b ? a : b; }

// Absolute slack for interpolation and conversion error, in depth units.
inline constexpr double kDepthSlack = 1.0 / 1024.0;

// Vulkan "Floating-Point Computation": for computation outside shaders such as the viewport and
// depth range calculations, "individual results of floating-point operations are accurate to about
// 1 part in 10^5". The depth intervals allow that relative error per operation.
inline constexpr double kSpecRelativeAccuracy = 1e-5;

// A primitive as the depth test sees it.
struct DepthPrimitive {
  std::vector<glm::dvec3> vertices;  // window x, y (pixels), z: 3 for a triangle, 2 for a line
  double line_width = 0;             // lines
  double box_half_px = 0;            // half-size of the judged pixel box
  double snap_px = 0;                // how far the device may move a vertex (snapping + slack)
  // Depth intervals only:
  double sample_half_px = 0;    // where in the pixel the device samples: 0 (the centre), or half the
                                // pixel box for multisampling (sample locations are not fixed)
  double source_max_abs_z = 0;  // largest finite |window z| of the primitive before clipping
  double clip_error_z = 0;      // window-z error the precision allows at vertices made by the clipper
  double clip_error_px = 0;     // and their window x, y error, in pixels
};

// The depth values a device may compute for a fragment of one primitive at one sample, before the
// conversion to the format (depth_format_interval), with the widening that dominated each end.
struct DepthValueRange {
  double lo = 0, hi = 0;
  DepthTerm lo_term = DepthTerm::Plane, hi_term = DepthTerm::Plane;
  double lo_widening = 0, hi_widening = 0;  // the dominating term's amount at each end
  bool any = false;                         // undefined (outside the depth range without depth clamp, no plane, ...)
};

struct DepthJudge {
  enum class Kind : uint8_t { Pass, Fail, Undefined, Compare };
  Kind kind = Kind::Pass;
  CompareOp op = CompareOp::Always;
  double clear = 1;
  double offset_lo = 0, offset_hi = 0;  // depth bias range
  bool clamp = false;
  double zmin = 0, zmax = 1;
  double slack = 0;                                   // interpolation error, before the clamp
  double unorm_step = 0;                              // one step of a UNORM format, 0 for D32
  double x0 = 0, y0 = 0, z0 = 0, dzdx = 0, dzdy = 0;  // z(p) = z0 + dzdx (x - x0) + dzdy (y - y0)
  double reach_px = 0;                                // widening of the plane value, in pixels of slope (see above)
  double range_lo = 0, range_hi = 0;                  // what the exact fragment depths can be (plus bias)
  // Depth intervals (fragment_depth_range):
  bool writes = false;  // a fragment that passes writes the depth attachment
  bool line = false;
  bool plane_defined = false;              // false: a flat triangle or point-like line with varying z
  DepthFormat format = DepthFormat::None;  // the attachment's format
  double vertex_lo = 0, vertex_hi = 0;     // the vertices' depths (no bias)
  double bias_lo = 0, bias_hi = 0;         // o over every r and m the spec allows, after dbclamp
  bool bias_any = false;                   // the slope term is unbounded (the snapped facing may flip)
  double vertex_error = 0;                 // precision allowance of the vertices' window z
  double coord_max = 0;                    // largest |window x|, |window y| of the vertices
  double reach_precision_px = 0;           // window x, y precision, in pixels
  double interval_reach_px = 0;            // widening of the plane value, in pixels of slope
};

// Vulkan "Depth Bias Computation": dbclamp(o) = min(o, clamp) for clamp > 0, max(o, clamp) for
// clamp < 0, o for 0 (or NaN).
double dbclamp(double o, float clamp);

DepthJudge make_depth_judge(const Scene& scene, const RasterState& state, const DepthPrimitive& primitive);

// The gate of a fragment of the primitive in the judged box centred on `pos_window`.
Gate depth_gate_at(const DepthJudge& judge, glm::dvec2 pos_window);

// The depth values a device may compute for a fragment of the primitive at a sample of the pixel
// box centred on `pos_window` (docs/spec-profile.md "Depth intervals"): the plane through every
// placement of the snapped vertices, within the vertices' depth range, plus the depth bias over
// every r and m the spec allows, widened by the spec's floating-point accuracy, then the depth clamp.
DepthValueRange fragment_depth_range(const DepthJudge& judge, glm::dvec2 pos_window);

// The raw stored values the conversion of `range` to the format may give (Vulkan "Conversion From
// Floating-Point to Normalized Fixed-Point": one of the two closest values; "Floating-Point Format
// Conversions": rounded to one or the other), with the same terms.
DepthInterval depth_format_interval(DepthFormat format, const DepthValueRange& range);

}  // namespace rastercmp::cpu::spec
