// One case: render a scene on the CPU (expected) and on the Vulkan device (actual), diff them
// and decide the verdict. Errors become verdicts, so a run goes on with the next scene:
//   NotSupportedError (CPU profile or device)  → NotSupported
//   DeviceError, out of memory                 → ResourceError
//   DeviceError, device lost                   → InternalError (the device is rebuilt for the next case)
//   validation-layer messages during the case  → InternalError
//   any other exception                        → InternalError
// InputError is not caught: a bad scene is the caller's to report before the run starts.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compare/case_result.hpp"
#include "compare/verdict.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp {

// "exact" when the CPU renders with the exact pipeline, else its method overrides in order,
// "STAGE=NAME" separated by spaces (command line first, then the scene's "methods").
std::string cpu_method_label(const CpuOptions& options);

// The CPU options for one scene (the command line merged with the scene's "methods").
using CpuOptionsForScene = std::function<CpuOptions(const Scene&)>;

class CaseRunner {
 public:
  // Creates the Vulkan device now. Throws EnvironmentError when there is none.
  CaseRunner(CompareProfile profile, CpuOptionsForScene cpu_options, VkOptions vk_options);
  ~CaseRunner();

  CompareProfile profile() const { return profile_; }
  const DeviceInfo& device() const { return device_; }

  // The CPU options used for a scene: the caller's, with the profile and the device's
  // sub-pixel precision applied.
  CpuOptions cpu_options(const Scene& scene) const;

  CaseResult run(const Scene& scene);

 private:
  VulkanRenderer& renderer();
  void render_both(const Scene& scene, CaseResult& result);

  CompareProfile profile_;
  CpuOptionsForScene cpu_options_;
  VkOptions vk_options_;
  std::unique_ptr<VulkanRenderer> renderer_;
  DeviceInfo device_;
};

}  // namespace rastercmp
