// Depth differences in the units a person reasons in: the stored format's step (LSB for
// UNORM, ULP for float) and the depth-bias unit r (Vulkan spec "Depth Bias").
// Input: two raw stored values of the same format. Output: plain numbers. No rounding of
// either value is done here; the raw bits are what the renderers stored.
#pragma once

#include <cstdint>

#include "model/scene.hpp"

namespace rastercmp {

// "LSB" for UNORM formats, "ULP" for D32_SFLOAT, "" for none.
const char* depth_unit_name(DepthFormat);

// |expected - actual| in the format's own step: LSB of the n-bit integer for UNORM, distance
// in representable floats (ULP) for D32_SFLOAT. Bits above the format's width are ignored.
uint64_t depth_diff_raw_units(DepthFormat, uint32_t expected_raw, uint32_t actual_raw);

// The minimum resolvable difference r at this pair of depths, as a depth value:
//   UNORM n bits: r = 2 / (2^n - 1), what lavapipe uses (docs/lavapipe-rules.md §4.3: 2 * mrd);
//   D32_SFLOAT:   r = 2^(e - 23), e the unbiased exponent of max(|expected|, |actual|)
//                 (spec "Depth Bias" for floating-point formats), e >= -126.
double depth_bias_r(DepthFormat, uint32_t expected_raw, uint32_t actual_raw);

// |expected - actual| in units of r (above). For a non-finite float difference the ULP
// distance stands in (within one binade the two measures agree).
double depth_diff_r_units(DepthFormat, uint32_t expected_raw, uint32_t actual_raw);

}  // namespace rastercmp
