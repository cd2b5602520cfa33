#include "compare/case_run.hpp"

#include <fmt/core.h>

#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/errors.hpp"
#include "model/file_read.hpp"
#include "model/image_io.hpp"

namespace rastercmp {

CaseRunner::CaseRunner(CompareProfile profile, CpuOptionsForScene cpu_options, VkOptions vk_options)
    : profile_(profile), cpu_options_(std::move(cpu_options)), vk_options_(std::move(vk_options)) {
  renderer_ = std::make_unique<VulkanRenderer>(vk_options_);
  device_ = renderer_->device();
}

CaseRunner::CaseRunner(CompareProfile profile, CpuOptionsForScene cpu_options, DeviceInfo device)
    : profile_(profile), cpu_options_(std::move(cpu_options)), device_(std::move(device)), from_captures_(true) {}

CaseRunner::~CaseRunner() = default;

DeviceInfo capture_device(const std::string& capture_dir) {
  const RenderResult r = read_render_info(capture_dir);
  DeviceInfo info;
  info.name = r.device_name.empty() ? r.device : r.device_name;
  info.driver_info = r.driver;
  info.limits = r.limits.value_or(DeviceLimits{});
  info.sub_pixel_precision_bits = info.limits.sub_pixel_precision_bits;
  info.fma = r.fma;
  return info;
}

std::string capture_dir_for(const std::string& root, const std::string& suite_dir, const std::string& scene_path) {
  namespace fs = std::filesystem;
  fs::path relative = fs::path(scene_path).lexically_proximate(suite_dir);
  // A scene file's folder drops ".json"; a model file keeps its extension, so duck.dae, duck.obj
  // and duck.json of one folder get three folders.
  if (relative.extension() == ".json") relative.replace_extension();
  return (fs::path(root) / relative).string();
}

CpuOptions CaseRunner::cpu_options(const Scene& scene) const {
  CpuOptions options = cpu_options_ ? cpu_options_(scene) : CpuOptions{};
  options.profile = profile_ == CompareProfile::Spec ? CpuProfile::Spec : CpuProfile::Lavapipe;
  if (options.lavapipe_from_driver) options.lavapipe = lavapipe_choice().release;
  // The spec profile judges the device with its own sub-pixel grid (CTS: subPixelPrecisionBits).
  // A capture without limits is judged with the specification's minimums (DeviceLimits).
  if (from_captures_ && capture_limits_) {
    options.sub_pixel_bits = capture_limits_->sub_pixel_precision_bits;
    options.viewport_sub_pixel_bits = capture_limits_->viewport_sub_pixel_bits;
  } else if (device_.sub_pixel_precision_bits != 0) {
    options.sub_pixel_bits = device_.sub_pixel_precision_bits;
    options.viewport_sub_pixel_bits = device_.limits.viewport_sub_pixel_bits;
  }
  return options;
}

LavapipeReleaseChoice CaseRunner::lavapipe_choice() const {
  // A capture names its driver; a worker judging captures has no device of its own.
  const std::string& driver = from_captures_ && !capture_driver_.empty() ? capture_driver_ : device_.driver_info;
  return lavapipe_release_for_driver(driver);
}

std::string CaseRunner::profile_name() const {
  if (profile_ == CompareProfile::Spec) return "spec";
  return cpu_options(Scene{}).lavapipe->profile;
}

VulkanRenderer& CaseRunner::renderer() {
  if (from_captures_) throw std::logic_error("CaseRunner::run on a runner made from captures");
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
    judge(scene, result);
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

namespace {

// not_supported.txt holds the device's one-line reason.
constexpr uint64_t kMaxMessageFileBytes = uint64_t(64) << 10;

std::string read_message_file(const std::string& path) {
  std::string message = read_bounded_file(path, kMaxMessageFileBytes, "a not_supported.txt message");
  while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
  return message.empty() ? "not supported" : message;
}

// Why a capture cannot be the scene's render (empty: it can). `expected` is the CPU's render of
// the scene: same size, sample count and depth format as the device's would be.
std::string capture_mismatch(const RenderResult& expected, const RenderResult& capture, const std::string& dir) {
  const std::string owner = (std::filesystem::path(dir) / "owner.tif").string();
  const std::string meta = (std::filesystem::path(dir) / "render.json").string();
  if (capture.width != expected.width || capture.height != expected.height || capture.samples != expected.samples)
    return fmt::format("{}: expected {}x{} with {} sample(s) as the scene, not {}x{} with {}", owner, expected.width,
                       expected.height, expected.samples, capture.width, capture.height, capture.samples);
  if (capture.depth_format != expected.depth_format)
    return fmt::format("{}: expected depth format {} as the scene, not {}", meta, to_string(expected.depth_format),
                       to_string(capture.depth_format));
  return "";
}

}  // namespace

void CaseRunner::judge(const Scene& scene, CaseResult& result) const {
  result.diff = diff_results(*result.expected, *result.actual, profile_);
  const VerdictDecision decision = decide_verdict(result.diff->summary, spec_depth_tolerance_r(scene),
                                                 result.cpu_method == "exact" ? Judged::Device : Judged::CpuMethod);
  result.verdict = decision.verdict;
  result.message = decision.message;
}

CaseResult CaseRunner::run_capture(const Scene& scene, const std::string& capture_dir) {
  namespace fs = std::filesystem;
  if (!from_captures_) throw std::logic_error("CaseRunner::run_capture on a runner made for a device");
  CaseResult result;
  // The capture first: its limits set the CPU options. Its errors wait until the CPU profile has
  // had its say, so a scene the profile cannot judge is NotSupported whatever was recorded.
  std::optional<RenderResult> capture;
  std::string device_not_supported, capture_error;
  const fs::path not_supported_file = fs::path(capture_dir) / kCaptureNotSupportedFile;
  if (fs::exists(not_supported_file)) {
    try {
      device_not_supported = read_message_file(not_supported_file.string());
    } catch (const InputError& e) {
      capture_error = e.what();
    }
  } else {
    try {
      capture = read_render_outputs(capture_dir);
    } catch (const InputError& e) {
      capture_error = e.what();
    }
  }
  capture_limits_ = capture ? capture->limits.value_or(DeviceLimits{}) : DeviceLimits{};
  capture_driver_ = capture ? capture->driver : "";
  result.cpu_method = cpu_method_label(cpu_options(scene));
  try {
    result.expected = render_cpu(scene, cpu_options(scene));
    if (!device_not_supported.empty()) {
      result.verdict = Verdict::NotSupported;
      result.message = "device: " + device_not_supported;
      return result;
    }
    if (!capture_error.empty()) {
      result.verdict = Verdict::ResourceError;
      result.message = "capture: " + capture_error;
      return result;
    }
    const std::string mismatch = capture_mismatch(*result.expected, *capture, capture_dir);
    if (!mismatch.empty()) {
      result.verdict = Verdict::ResourceError;
      result.message = "capture: " + mismatch;
      return result;
    }
    result.actual = std::move(*capture);
    judge(scene, result);
  } catch (const InputError&) {
    throw;
  } catch (const NotSupportedError& e) {
    result.verdict = Verdict::NotSupported;
    result.message = fmt::format("cpu profile: {}", e.what());
  } catch (const std::exception& e) {
    result.verdict = Verdict::InternalError;
    result.message = e.what();
  }
  return result;
}

}  // namespace rastercmp
