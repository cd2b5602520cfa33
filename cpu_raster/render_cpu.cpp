// render_cpu: the CPU renderer's façade (cpu_raster/cpu_raster.hpp). It picks the layer that
// renders; each layer depends on the exact path only, never on this file or on each other.
#include "cpu_raster/cpu_raster.hpp"

#include <algorithm>
#include <array>

#include "cpu_raster/classic/classic_methods.hpp"
#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/exact/render_exact.hpp"
#include "cpu_raster/fast/render_fast.hpp"
#include "cpu_raster/spec/coverage_map.hpp"
#include "cpu_raster/spec/exact_owners.hpp"
#include "cpu_raster/spec/open_owners.hpp"
#include "cpu_raster/spec/spec_primitives.hpp"
#include "cpu_raster/spec/spec_profile.hpp"
#include "cpu_raster/spec/subpixel.hpp"
#include "model/errors.hpp"

namespace rastercmp {
namespace {

// The lavapipe profile: the fast path with options.threads workers, or the exact path.
RenderResult render_lavapipe_profile(const Scene& scene, const CpuOptions& options) {
  if (options.threads >= 1) return render_cpu_fast(scene, options);  // cpu_raster/fast/
  return render_exact(scene, options);                               // cpu_raster/exact/
}

// The spec profile: coverage classes over the lavapipe profile's render as the estimate.
RenderResult render_spec(const Scene& scene, const CpuOptions& options) {
  check_spec_profile_support(scene);
  CpuOptions estimate = options;
  estimate.profile = CpuProfile::Lavapipe;
  return render_spec_profile(scene, options, render_lavapipe_profile(scene, estimate));  // cpu_raster/spec/
}

}  // namespace

RenderResult render_cpu(const Scene& scene, const CpuOptions& options) {
  if (uses_classic_methods(options)) return render_classic(scene, options);  // cpu_raster/classic/
  if (options.profile == CpuProfile::Spec) return render_spec(scene, options);
  return render_lavapipe_profile(scene, options);
}

std::vector<ExactDeviceOwner> exact_device_owners_at(const Scene& scene, const CpuOptions& options, uint32_t x,
                                                     uint32_t y, uint32_t sample) {
  check_spec_profile_support(scene);
  const uint32_t bits = cpu::spec::effective_sub_pixel_bits(options.sub_pixel_bits);
  const cpu::spec::SpecPrimitives primitives = cpu::spec::build_spec_primitives(scene, options.fma, bits);
  std::vector<ExactDeviceOwner> out;
  if (primitives.undefined) return out;  // not simulated (exact_owners.hpp)
  for (const cpu::spec::ExactDevice& device : cpu::spec::exact_devices(scene))
    out.push_back({cpu::spec::describe_exact_device(scene, device),
                   cpu::spec::exact_device_owner(scene, primitives.triangles, bits, device, x, y, sample)});
  return out;
}

SpecPixelRules spec_pixel_rules(const Scene& scene, const CpuOptions& options, const RenderResult& expected, uint32_t x,
                                uint32_t y) {
  check_spec_profile_support(scene);
  static constexpr std::array<const char*, 3> kCoverage = {"none", "partial", "full"};
  static constexpr std::array<const char*, 3> kGate = {"never", "maybe", "certain"};
  const uint32_t bits = cpu::spec::effective_sub_pixel_bits(options.sub_pixel_bits);
  const cpu::spec::SpecPrimitives primitives = cpu::spec::build_spec_primitives(scene, options.fma, bits);
  SpecPixelRules rules;
  const cpu::PixelRect region = cpu::spec::scissor_region(scene);
  rules.in_scissor =
      int32_t(x) >= region.x0 && int32_t(x) <= region.x1 && int32_t(y) >= region.y0 && int32_t(y) <= region.y1;
  rules.undefined = primitives.undefined;
  for (const cpu::spec::PrimitiveAtPixel& p : cpu::spec::primitives_at(scene, primitives, bits, int32_t(x), int32_t(y)))
    rules.primitives.push_back({p.owner, p.line, kCoverage[size_t(p.coverage)], kGate[size_t(p.gate)]});
  rules.viewports = spec_viewport_representations(scene, options).size();
  if (!expected.coverage_class.empty()) {
    const std::vector<uint32_t> open =
        cpu::spec::open_owner_pixels(scene, primitives, expected.coverage_class, expected.owner, bits);
    rules.owner_open = std::binary_search(open.begin(), open.end(), y * scene.width + x);
    if (rules.owner_open) {
      const bool line_near = std::any_of(rules.primitives.begin(), rules.primitives.end(),
                                         [](const auto& p) { return p.line && p.coverage != "none"; });
      rules.open_reason = line_near ? "a line may cover the pixel, and its shape there is the device's choice"
                                    : "the estimate's owner is a primitive that may not cover the pixel (a deviation "
                                      "of the modelled lavapipe release)";
    }
  }
  return rules;
}

std::string method_choice_problem(const MethodChoice& choice) {
  try {
    cpu::classic::parse_classic_methods({choice});  // the registry: throws naming the known names
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace rastercmp
