#include "experiments/depth_r.hpp"

#include <cmath>

#include "cpu_raster/cpu_raster.hpp"
#include "experiments/scene_make.hpp"
#include "experiments/sweep_common.hpp"
#include "model/depth_format.hpp"

namespace rastercmp::experiments {
namespace {

// Centre pixel of the flat plane (inside the 48x48 square).
struct Step {
  double value = 0, raw = 0;
};

Step centre_step(const RenderResult& biased, const RenderResult& plain) {
  const size_t i = biased.index(biased.width / 2, biased.height / 2);
  return {depth_raw_to_value(biased.depth_format, biased.depth_raw[i]) -
              depth_raw_to_value(plain.depth_format, plain.depth_raw[i]),
          double(biased.depth_raw[i]) - double(plain.depth_raw[i])};
}

}  // namespace

std::vector<DepthRMeasure> measure_depth_r(VulkanRenderer& vk) {
  std::vector<DepthRMeasure> out;
  for (DepthFormat format : sweep_depth_formats()) {
    DepthBias bias;
    bias.enable = true;
    bias.constant_factor = 1;  // towards the far plane: +r on a Less test with depth 0.375
    const Scene plain = make_flat_plane(format, DepthBias{});
    const Scene biased = make_flat_plane(format, bias);
    const BackendPair p = render_both(vk, plain);
    const BackendPair b = render_both(vk, biased);
    const Step cpu = centre_step(b.cpu, p.cpu), gpu = centre_step(b.vk, p.vk);
    DepthRMeasure m;
    m.format = format;
    m.r_cpu = cpu.value;
    m.r_vk = gpu.value;
    m.raw_step_cpu = cpu.raw;
    m.raw_step_vk = gpu.raw;
    const DepthFormatInfo info = depth_format_info(format);
    if (info.encoding == DepthEncoding::Float) {
      // 0.375 = 0.75 * 2^-1: unbiased exponent e = -2; r = 2^(e-n) (docs/lavapipe-rules.md §4.1)
      m.spec_bound = float_depth_r(info, double(kFlatPlaneDepth));
      m.lavapipe_formula = m.spec_bound;  // docs/lavapipe-rules.md §4.3, float branch
    } else {
      m.spec_bound = 2.0 * std::ldexp(1.0, -int(info.bits));  // spec: r <= 2 x 2^-n (§4.1)
      m.lavapipe_formula = 2.0 * info.mrd;                    // lavapipe: 2 * mrd (§4.3)
    }
    out.push_back(m);
  }
  return out;
}

}  // namespace rastercmp::experiments
