#include "compare/case_run.hpp"

#include <fmt/core.h>

#include <exception>

#include "model/errors.hpp"

namespace rastercmp {

CaseRunner::CaseRunner(CompareProfile profile, CpuOptionsForScene cpu_options, VkOptions vk_options)
    : profile_(profile), cpu_options_(std::move(cpu_options)), vk_options_(std::move(vk_options)) {
  renderer_ = std::make_unique<VulkanRenderer>(vk_options_);
  device_ = renderer_->device();
}

CaseRunner::~CaseRunner() = default;

CpuOptions CaseRunner::cpu_options(const Scene& scene) const {
  CpuOptions options = cpu_options_ ? cpu_options_(scene) : CpuOptions{};
  options.profile = profile_ == CompareProfile::Spec ? CpuProfile::Spec : CpuProfile::Lavapipe;
  // The spec profile judges the device with its own sub-pixel grid (CTS: subPixelPrecisionBits).
  if (device_.sub_pixel_precision_bits != 0) options.sub_pixel_bits = device_.sub_pixel_precision_bits;
  return options;
}

VulkanRenderer& CaseRunner::renderer() {
  if (!renderer_) renderer_ = std::make_unique<VulkanRenderer>(vk_options_);  // after a device loss
  return *renderer_;
}

void CaseRunner::render_both(const Scene& scene, CaseResult& result) {
  result.expected = render_cpu(scene, cpu_options(scene));
  VulkanRenderer& vk = renderer();
  const size_t messages_before = vk.validation_messages().size();
  result.actual = vk.render(scene);
  const auto& messages = vk.validation_messages();
  result.validation_messages.assign(messages.begin() + std::ptrdiff_t(messages_before), messages.end());
}

std::string cpu_method_label(const CpuOptions& options) {
  std::string label;
  for (const MethodChoice& choice : options.methods)
    label += (label.empty() ? "" : " ") + choice.stage + "=" + choice.name;
  return label.empty() ? "exact" : label;
}

CaseResult CaseRunner::run(const Scene& scene) {
  CaseResult result;
  result.cpu_method = cpu_method_label(cpu_options(scene));
  try {
    render_both(scene, result);
    if (!result.validation_messages.empty()) {
      result.verdict = Verdict::InternalError;
      result.message = fmt::format("{} validation message(s): {}", result.validation_messages.size(),
                                   result.validation_messages.front());
      return result;
    }
    result.diff = diff_results(*result.expected, *result.actual, profile_);
    const VerdictDecision decision = decide_verdict(result.diff->summary, spec_depth_tolerance_r(scene));
    result.verdict = decision.verdict;
    result.message = decision.message;
  } catch (const InputError&) {
    throw;
  } catch (const NotSupportedError& e) {
    result.verdict = Verdict::NotSupported;
    result.message = fmt::format("{}: {}", result.expected ? "device" : "cpu profile", e.what());
  } catch (const DeviceError& e) {
    result.verdict = e.out_of_memory() ? Verdict::ResourceError : Verdict::InternalError;
    result.message = fmt::format("device: {}", e.what());
    if (!e.out_of_memory()) renderer_.reset();  // device lost: rebuild it for the next case
  } catch (const std::exception& e) {
    result.verdict = Verdict::InternalError;
    result.message = e.what();
  }
  return result;
}

}  // namespace rastercmp
