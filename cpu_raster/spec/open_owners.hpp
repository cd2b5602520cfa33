// Owners the exact devices do not settle (docs/spec-profile.md "Owners", open samples).
//
// exact_owners.hpp simulates devices that draw triangles. Two kinds of Must pixel lie outside what
// that simulation can decide:
//  - pixels a line may cover: the line rules leave the shape to the device (rectangle or
//    parallelogram when strictLines is unknown, Bresenham's diamond exit, the caps, whether a
//    line with a vertex outside the clip volume is clipped: "Basic Line Segment Rasterization",
//    "Primitive Clipping"), so whether the line's fragment is there is the device's choice;
//  - pixels where the estimate's owner is a primitive the classification does not let cover the
//    pixel at all: the modelled lavapipe release deviates there (for example a line through
//    w = 0 drawn between its projected ends, docs/lavapipe-rules.md §8.2), so the estimate says
//    nothing about the owner.
// At such a pixel the owner is open: any primitive that may cover the pixel is an alternative
// unless a primitive that certainly covers it (FULL, certain gate) certainly beats it in the depth
// test whatever the device chose. "Certainly beats", with the raw depth intervals of the two
// fragments at the pixel (depth_intervals.hpp):
//  - C after P: C's test is off or ALWAYS, or P writes its depth and C's ordered compare passes
//    against every depth P may have stored (every fragment between them that P's owner survives
//    failed, so the stored value is P's);
//  - C before P: C writes its depth with LESS or LESS_OR_EQUAL, every draw from C's to P's that
//    writes depth keeps the stored value from rising (LESS, LESS_OR_EQUAL, EQUAL), so at P it is
//    at most C's upper bound, and P's LESS, LESS_OR_EQUAL or EQUAL fails against every such
//    value; the same with GREATER, GREATER_OR_EQUAL mirrored.
// A relaxation like the simulation: an alternative only ever replaces a QualityWarning. What it
// leaves out: which of two friends along a shared edge covers (each alone is uncertain there), so a
// primitive behind them is not ruled out at an open pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "cpu_raster/spec/spec_primitives.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::spec {

// Upper bound of primitive x open-pixel visits; beyond it no open alternatives are computed
// (conservative: fewer alternatives, more QualityWarnings).
inline constexpr uint64_t kOpenOwnerWorkLimit = uint64_t(1) << 24;

// The open Must pixels (indices y * width + x, ascending), from the classes (RenderResult order)
// and the estimate's owners.
std::vector<uint32_t> open_owner_pixels(const Scene& scene, const SpecPrimitives& primitives,
                                        const std::vector<CoverageClass>& classes, const PixelBuffer& estimate_owner,
                                        uint32_t sub_pixel_bits);

// For every sample of the open pixels, the owners other than `estimate_owner[sample]` that the rule
// above allows, sorted by sample and owner.
std::vector<OwnerAlternative> open_owner_alternatives(const Scene& scene, const SpecPrimitives& primitives,
                                                      uint32_t sub_pixel_bits, const std::vector<uint32_t>& open_pixels,
                                                      const PixelBuffer& estimate_owner);

// What one primitive may do at one pixel (rastercmp explain): its own class there and its gate.
struct PrimitiveAtPixel {
  uint32_t owner = 0;
  bool line = false;
  Coverage coverage = Coverage::None;
  Gate gate = Gate::Never;
};

// Every primitive whose reach holds pixel (px, py), in submission order.
std::vector<PrimitiveAtPixel> primitives_at(const Scene& scene, const SpecPrimitives& primitives,
                                            uint32_t sub_pixel_bits, int32_t px, int32_t py);

}  // namespace rastercmp::cpu::spec
