// r, the minimum resolvable depth difference of the constant depth-bias term, measured from what
// each backend writes: a flat plane at window depth 0.375 with constantFactor 1 against 0.
#pragma once

#include <vector>

#include "model/scene.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::experiments {

struct DepthRMeasure {
  DepthFormat format = DepthFormat::D16Unorm;
  double r_cpu = 0, r_vk = 0;                // depth value step per unit of constant factor (K = 1)
  double raw_step_cpu = 0, raw_step_vk = 0;  // raw stored bits step for K = 1
  double spec_bound = 0;                     // UNORM: 2 * 2^-n; D32: 2^(e-23), e = exponent of 0.375
  double lavapipe_formula = 0;               // UNORM: 2 / (2^n - 1) (docs/lavapipe-rules.md §4.3); D32: 2^(e-23)
};

std::vector<DepthRMeasure> measure_depth_r(VulkanRenderer& vk);

}  // namespace rastercmp::experiments
