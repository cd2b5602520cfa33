// VulkanRenderer: the public face of the reference (vk_reference.hpp). One instance and device per
// renderer; render passes cached for its life, pipelines in a bounded cache (vk_pipeline.hpp); each scene a Frame.
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include "vk_reference/vk_context.hpp"
#include "vk_reference/vk_device_info.hpp"
#include "vk_reference/vk_frame.hpp"
#include "vk_reference/vk_gather.hpp"
#include "vk_reference/vk_instance.hpp"
#include "vk_reference/vk_pipeline.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp {

std::vector<DeviceInfo> list_vulkan_devices() {
  const vk::Instance instance(/*validate=*/false);
  const std::vector<VkPhysicalDevice> devices = instance.physical_devices();
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(vk::describe_device(devices[i], i));
  return infos;
}

struct VulkanRenderer::Impl {
  explicit Impl(const VkOptions& options) : context(options), pipelines(context, options.max_cached_pipelines) {}

  vk::Context context;
  vk::PipelineCache pipelines;
  std::unique_ptr<vk::SampleGather> owner_gather;  // made on the first multisampled scene
  std::unique_ptr<vk::SampleGather> depth_gather;  // made on the first multisampled scene with depth
  // How the device samples each UNORM depth format, measured on its first multisampled scene.
  std::map<DepthFormat, std::optional<vk::UnormSampling>> unorm_sampling;
};

namespace {

vk::Frame& as_frame(VulkanRenderer::Prepared& prepared) {
  auto* frame = dynamic_cast<vk::Frame*>(&prepared);
  if (frame == nullptr) throw std::invalid_argument("VulkanRenderer: Prepared object from another renderer type");
  return *frame;
}

}  // namespace

VulkanRenderer::VulkanRenderer(const VkOptions& options) : impl_(std::make_unique<Impl>(options)) {}

VulkanRenderer::~VulkanRenderer() = default;

const DeviceInfo& VulkanRenderer::device() const { return impl_->context.info(); }

RenderResult VulkanRenderer::render(const Scene& scene) {
  const std::unique_ptr<Prepared> prepared = prepare(scene);
  submit_and_wait_seconds(*prepared);
  return read_back(*prepared);
}

std::unique_ptr<VulkanRenderer::Prepared> VulkanRenderer::prepare(const Scene& scene) {
  if (scene.samples > 1 && !impl_->owner_gather) {
    impl_->owner_gather = std::make_unique<vk::SampleGather>(impl_->context, vk::GatherKind::Owner);
  }
  if (scene.samples > 1 && scene.depth_format != DepthFormat::None && !impl_->depth_gather) {
    impl_->depth_gather = std::make_unique<vk::SampleGather>(impl_->context, vk::GatherKind::Depth);
  }
  impl_->pipelines.trim();  // between frames only (vk_pipeline.hpp)
  vk::Gathers gathers{impl_->owner_gather.get(), impl_->depth_gather.get(), std::nullopt};
  if (scene.samples > 1 && depth_format_info(scene.depth_format).encoding == DepthEncoding::Unorm) {
    if (!impl_->unorm_sampling.contains(scene.depth_format))
      impl_->unorm_sampling[scene.depth_format] = vk::measure_unorm_sampling(impl_->context, scene.depth_format);
    gathers.depth_sampling = impl_->unorm_sampling[scene.depth_format];
  }
  return std::make_unique<vk::Frame>(impl_->context, impl_->pipelines, gathers, scene);
}

double VulkanRenderer::submit_and_wait_seconds(Prepared& prepared) { return as_frame(prepared).submit_and_wait(); }

RenderResult VulkanRenderer::read_back(Prepared& prepared) { return as_frame(prepared).read_back(); }

const std::vector<std::string>& VulkanRenderer::validation_messages() const {
  return impl_->context.validation_messages();
}

size_t VulkanRenderer::cached_pipelines() const { return impl_->pipelines.pipeline_count(); }

}  // namespace rastercmp
