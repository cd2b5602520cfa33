// Which primitive a device that evaluates the specification's equations exactly may leave as the
// owner of a sample, beyond the estimate's choice (docs/spec-profile.md "Owners").
//
// Where two primitives may both cover a Must sample, which one the device leaves there depends on
// the depth test between them, and that on choices the specification leaves to the implementation
// as rules, not as precision:
//  - the rounding of vertex positions to the subPixelPrecisionBits grid (Vulkan "Controlling the
//    Viewport": x_f and y_f "have limited precision"; no rounding mode is given), so each
//    primitive's depth plane, interpolated over its snapped vertices ("Basic Polygon
//    Rasterization": z = a z_a + b z_b + c z_c with the barycentrics of the framebuffer-coordinate
//    vertices), tilts a little differently;
//  - the tie rule for a sample on a common edge ("exactly one of the polygons must result in a
//    covered sample"; no rule is mandated);
//  - r and m of depth bias ("Depth Bias Computation": r "is implementation-dependent but must be
//    at most" 2 x 2^-n, at least 2^-n; float: 2^(e-n), which may be scaled without
//    depthBiasExact; m "may be approximated");
//  - the rounding of a float depth to D32 ("rounded to one or the other. The rounding mode is not
//    defined"). UNORM conversion keeps round to nearest, which the specification recommends
//    ("Implementations should round to nearest").
// A device that makes these choices and then computes without error is as exact as a device can
// be, so an owner it gives is not a matter of quality. Each combination below is one such device
// (exact_devices()); they are simulated sample by sample where the classes leave a choice: Must
// pixels that two or more triangles may cover. An owner none of them gives is left to
// compare/ as a wrong owner: only arithmetic error can put it there, which the specification
// leaves to quality (for example between coplanar primitives that share their vertices).
//
// Per sample, so a relaxation like the coverage classes: two neighbouring samples may be explained
// by two different devices. Lines are not simulated: where a line may cover a sample the owner is
// judged by open_owners.hpp instead. Not simulated (no alternatives): scenes with undefined
// primitives, and scenes whose contested work exceeds kExactOwnerWorkLimit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cpu_raster/spec/spec_primitives.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::spec {

enum class SnapRounding : uint8_t { Nearest, Floor, Ceil };
enum class TieRule : uint8_t { TopLeft, BottomRight };
enum class FloatRounding : uint8_t { Nearest, Down, Up };

// One exactly computing device: its choices where the specification leaves them open.
struct ExactDevice {
  SnapRounding snap = SnapRounding::Nearest;
  TieRule tie = TieRule::TopLeft;
  // Depth bias, two choices apart: r at its upper end (2 x 2^-n, or 2 x 2^(e-n)) or lower (2^-n,
  // 2^(e-n)); m in its sqrt form or the max form the specification lets it be approximated by.
  bool bias_r_high = false;
  bool bias_m_sqrt = false;
  FloatRounding d32 = FloatRounding::Nearest;
};

// The devices simulated for a scene: every snapping rounding with the top-left tie rule, nearest
// with bottom-right; times both ends of r and both forms of m when a draw has depth bias; times the
// three D32 roundings for a D32 attachment.
std::vector<ExactDevice> exact_devices(const Scene& scene);

// A device's choices in words, those exact_devices(scene) varies: "floor vertex rounding,
// top-left tie rule", plus "bias r at its upper end, m in its sqrt form" with depth bias and "D32 rounding
// up" with a D32 attachment (rastercmp explain, docs/compare.md).
std::string describe_exact_device(const Scene& scene, const ExactDevice& device);

// Upper bound of candidate x sample x device evaluations; beyond it no alternatives are computed.
inline constexpr uint64_t kExactOwnerWorkLimit = uint64_t(1) << 26;

// For every sample of the `contested` pixels (indices y * width + x, ascending), the owners other
// than `estimate_owner[sample]` that some exact device leaves there, sorted by sample and owner.
// `triangles` in draw order (build_spec_primitives).
std::vector<OwnerAlternative> exact_owner_alternatives(const Scene& scene, const std::vector<SpecTriangle>& triangles,
                                                       uint32_t sub_pixel_bits, const std::vector<uint32_t>& contested,
                                                       const PixelBuffer& estimate_owner);

// One device's owner of one sample (tests): the last of `triangles` whose fragment covers the
// sample and passes the depth test, or kOwnerBackground. No scissor.
uint32_t exact_device_owner(const Scene& scene, const std::vector<SpecTriangle>& triangles, uint32_t sub_pixel_bits,
                            const ExactDevice& device, uint32_t x, uint32_t y, uint32_t sample);

// One device's owners of every sample (RenderResult order), the scissor applied (tests).
std::vector<uint32_t> exact_device_owners(const Scene& scene, const std::vector<SpecTriangle>& triangles,
                                          uint32_t sub_pixel_bits, const ExactDevice& device);

}  // namespace rastercmp::cpu::spec
