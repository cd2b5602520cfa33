// One case: render a scene on the CPU (expected) and on the Vulkan device (actual), diff them
// and decide the verdict. Errors become verdicts, so a run goes on with the next scene:
//   NotSupportedError (CPU profile or device)  → NotSupported
//   DeviceError, out of memory                 → ResourceError
//   DeviceError, device lost                   → InternalError (the device is rebuilt for the next case)
//   validation-layer messages during the case  → InternalError
//   any other exception                        → InternalError
// InputError is not caught: a bad scene is the caller's to report before the run starts.
// A runner made from a capture judges recorded renders instead (`rastercmp capture`, docs/compare.md):
//   capture folder holds not_supported.txt                    → NotSupported (the device's message)
//   render.json / owner.tif / depth_raw.tif missing, corrupt,
//   or of another size, sample count or depth format          → ResourceError naming the file
// and the spec profile takes subPixelPrecisionBits from each capture's limits (8 when absent).
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
  // Judges captures: no device is created; `device` describes the recorded one (capture_device).
  CaseRunner(CompareProfile profile, CpuOptionsForScene cpu_options, DeviceInfo device);
  ~CaseRunner();

  CompareProfile profile() const { return profile_; }
  const DeviceInfo& device() const { return device_; }

  // The CPU options used for a scene: the caller's, with the profile and the device's
  // sub-pixel precision applied.
  CpuOptions cpu_options(const Scene& scene) const;
  // The lavapipe release the device's driver (or the last capture's) is judged by, and why not
  // its own when it is not modelled (compare/run_info.hpp carries the warning to every output).
  LavapipeReleaseChoice lavapipe_choice() const;
  // "spec", or the lavapipe release the CPU reproduces: "lavapipe-25.0".
  std::string profile_name() const;

  CaseResult run(const Scene& scene);
  // The same verdicts for the render recorded in `capture_dir` (a runner made from a capture).
  CaseResult run_capture(const Scene& scene, const std::string& capture_dir);

 private:
  VulkanRenderer& renderer();
  void render_both(const Scene& scene, CaseResult& result);
  void judge(const Scene& scene, CaseResult& result) const;  // diff and verdict of the two renders

  CompareProfile profile_;
  CpuOptionsForScene cpu_options_;
  VkOptions vk_options_;
  std::unique_ptr<VulkanRenderer> renderer_;
  DeviceInfo device_;
  bool from_captures_ = false;
  std::optional<DeviceLimits> capture_limits_;  // the last capture's, for cpu_options
  std::string capture_driver_;                  // the last capture's driver info, for cpu_options
};

// The device a capture folder's render.json names (name, driver, limits; sub-pixel bits 8 when
// it records none). Throws InputError when render.json is missing or unreadable.
DeviceInfo capture_device(const std::string& capture_dir);

// Where a suite case's capture lies: ROOT/<scene path relative to the suite, without .json; a
// model file with its extension>.
std::string capture_dir_for(const std::string& root, const std::string& suite_dir, const std::string& scene_path);

// What `rastercmp capture` writes into a capture folder in place of a render the device refused
// (NotSupportedError): its message.
inline constexpr const char* kCaptureNotSupportedFile = "not_supported.txt";

}  // namespace rastercmp
