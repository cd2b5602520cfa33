#include "vk_reference/vk_frame.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fmt/core.h>

#include "model/errors.hpp"
#include "vk_reference/vk_check.hpp"
#include "vk_reference/vk_loader.hpp"
#include "vk_reference/vk_translate.hpp"

namespace rastercmp::vk {
namespace {

static_assert(sizeof(glm::vec4) == 4 * sizeof(float), "positions_clip must upload as packed vec4");

Geometry upload_geometry(const Context& context, PipelineCache& pipelines, const AttachmentConfig& config,
                         const Scene& scene) {
  Geometry geometry;
  VkDeviceSize vertex_bytes = 0, index_bytes = 0;
  for (const Draw& draw : scene.draws) {
    DrawCall call;
    call.vertex_offset = vertex_bytes;
    call.index_offset = index_bytes;
    call.vertex_count = draw.vertex_count();
    call.indexed = !draw.indices.empty();
    if (draw.state.depth_bias.enable) call.depth_bias = draw.state.depth_bias;
    if (call.vertex_count > 0) call.pipeline = pipelines.graphics_pipeline(config, draw.topology, draw.state);
    vertex_bytes += draw.positions_clip.size() * sizeof(glm::vec4);
    index_bytes += draw.indices.size() * sizeof(uint32_t);
    geometry.calls.push_back(call);
  }
  // A buffer may not be empty; a scene of empty draws still gets a (never read) vertex buffer.
  geometry.vertices = create_host_buffer(context, std::max<VkDeviceSize>(vertex_bytes, sizeof(glm::vec4)),
                                         VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  if (index_bytes > 0) geometry.indices = create_host_buffer(context, index_bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  for (size_t i = 0; i < scene.draws.size(); ++i) {
    const Draw& draw = scene.draws[i];
    const DrawCall& call = geometry.calls[i];
    std::memcpy(static_cast<unsigned char*>(geometry.vertices.mapped) + call.vertex_offset, draw.positions_clip.data(),
                draw.positions_clip.size() * sizeof(glm::vec4));
    if (call.indexed) {
      std::memcpy(static_cast<unsigned char*>(geometry.indices->mapped) + call.index_offset, draw.indices.data(),
                  draw.indices.size() * sizeof(uint32_t));
    }
  }
  return geometry;
}

ReadBack create_read_back(const Context& context, const Gathers& gathers, const Attachments& attachments,
                          const AttachmentConfig& config, uint32_t width, uint32_t height) {
  ReadBack read_back;
  const VkDeviceSize texels = VkDeviceSize(width) * height;
  if (config.samples == 1) {
    read_back.owner = create_host_buffer(context, texels * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    if (config.depth_format != DepthFormat::None) {
      read_back.depth = create_host_buffer(context, texels * depth_copy_texel_bytes(config.depth_format),
                                           VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    }
    return read_back;
  }
  if (gathers.owner == nullptr) throw std::logic_error("Frame: a multisampled scene needs the owner gather pipeline");
  const VkDeviceSize sample_bytes = texels * config.samples * sizeof(uint32_t);
  read_back.owner = create_host_buffer(context, sample_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  read_back.gather = gathers.owner->bind(attachments.owner.view.get(), read_back.owner, width, height, config.samples);
  if (attachments.depth_sampled) {
    if (gathers.depth == nullptr) throw std::logic_error("Frame: multisampled depth needs the depth gather pipeline");
    read_back.depth = create_host_buffer(context, sample_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    read_back.depth_gather =
        gathers.depth->bind(attachments.depth->view.get(), *read_back.depth, width, height, config.samples);
  }
  return read_back;
}

// The viewport must be one Vulkan accepts (VkViewport valid usage): lavapipe does not reject an
// invalid one, it crashes or draws garbage, so it is refused here as bad input.
void check_viewport(const Scene& scene, const VkPhysicalDeviceLimits& limits) {
  const Viewport v = scene.effective_viewport();
  const std::string& file = scene.source_path;
  const float lo = limits.viewportBoundsRange[0], hi = limits.viewportBoundsRange[1];
  const auto in = [](float value, float min, float max) { return value >= min && value <= max; };  // false for NaN
  if (!(v.width > 0.0f && v.width <= float(limits.maxViewportDimensions[0]))) {
    throw InputError(file, "$.viewport.width", fmt::format("a width in (0, {}]", limits.maxViewportDimensions[0]));
  }
  if (!(v.height != 0.0f && std::abs(v.height) <= float(limits.maxViewportDimensions[1]))) {
    throw InputError(file, "$.viewport.height",
                     fmt::format("a non-zero height of magnitude at most {}", limits.maxViewportDimensions[1]));
  }
  if (!in(v.x, lo, hi) || !in(v.x + v.width, lo, hi)) {
    throw InputError(file, "$.viewport.x", fmt::format("x and x + width within [{}, {}]", lo, hi));
  }
  if (!in(v.y, lo, hi) || !in(v.y + v.height, lo, hi)) {
    throw InputError(file, "$.viewport.y", fmt::format("y and y + height within [{}, {}]", lo, hi));
  }
  // Without VK_EXT_depth_range_unrestricted (deliberately off) depths must lie in [0, 1].
  if (!in(v.min_depth, 0.0f, 1.0f)) throw InputError(file, "$.viewport.min_depth", "a number in [0, 1]");
  if (!in(v.max_depth, 0.0f, 1.0f)) throw InputError(file, "$.viewport.max_depth", "a number in [0, 1]");
}

}  // namespace

void check_scene(const Scene& scene) {
  const std::string& file = scene.source_path;
  const std::string side = fmt::format("an integer 1..{}", kMaxFramebufferSide);
  if (scene.width < 1 || scene.width > kMaxFramebufferSide) throw InputError(file, "$.width", side);
  if (scene.height < 1 || scene.height > kMaxFramebufferSide) throw InputError(file, "$.height", side);
  if (!(scene.depth_clear >= 0.0f && scene.depth_clear <= 1.0f)) {
    throw InputError(file, "$.depth_clear", "a number in [0, 1]");  // VkClearDepthStencilValue
  }
  if (scene.draws.size() > kMaxDraws) throw InputError(file, "$.draws", fmt::format("at most {} draws", kMaxDraws));
  for (size_t d = 0; d < scene.draws.size(); ++d) {
    const Draw& draw = scene.draws[d];
    for (size_t i = 0; i < draw.indices.size(); ++i) {
      if (draw.indices[i] >= draw.positions_clip.size()) {
        throw InputError(file, fmt::format("$.draws[{}].indices[{}]", d, i),
                         fmt::format("an index below the draw's {} positions", draw.positions_clip.size()));
      }
    }
  }
}

Frame::Frame(const Context& context, PipelineCache& pipelines, const Gathers& gathers, const Scene& scene)
    : context_(context),
      pin_(pipelines),
      width_(scene.width),
      height_(scene.height),
      samples_(scene.samples),
      depth_format_(scene.depth_format),
      depth_sampling_(gathers.depth_sampling) {
  check_scene(scene);
  check_viewport(scene, context.enabled().limits);
  const AttachmentConfig config{depth_format_, samples_};
  require_attachment_support(context, config, width_, height_);
  const VkRenderPass render_pass = pipelines.render_pass(config);
  geometry_ = upload_geometry(context, pipelines, config, scene);  // NotSupportedError before big allocations
  // Multisampled UNORM depth is read back only where the device's conversion to float is known.
  const bool unorm = depth_format_info(depth_format_).encoding == DepthEncoding::Unorm;
  const bool sampled_depth =
      multisampled_depth_readable(context, config, width_, height_) && (!unorm || depth_sampling_.has_value());
  attachments_ = create_attachments(context, render_pass, config, width_, height_, sampled_depth);
  read_back_ = create_read_back(context, gathers, attachments_, config, width_, height_);
  commands_ = allocate_commands(context);
  fence_ = create_fence(context);

  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  check(api().vkBeginCommandBuffer(commands_.get(), &begin), "vkBeginCommandBuffer");
  record_frame(commands_.get(), scene, render_pass, pipelines.graphics_layout(), attachments_, geometry_, read_back_,
               gathers);
  check(api().vkEndCommandBuffer(commands_.get()), "vkEndCommandBuffer");
}

double Frame::submit_and_wait() {
  const VkDevice device = context_.device();
  const VkFence fence = fence_.get();
  const VkCommandBuffer commands = commands_.get();
  check(api().vkResetFences(device, 1, &fence), "vkResetFences");
  const auto start = std::chrono::steady_clock::now();
  vk::submit_and_wait(context_, commands, fence);
  const auto stop = std::chrono::steady_clock::now();
  submitted_ = true;
  return std::chrono::duration<double>(stop - start).count();
}

RenderResult Frame::read_back() const {
  if (!submitted_) throw std::logic_error("VulkanRenderer::read_back before submit_and_wait_seconds");
  const DeviceInfo& info = context_.info();
  RenderResult result;
  result.backend = "vulkan";
  result.device = info.driver_info.empty() ? info.name : info.name + " (" + info.driver_info + ")";
  result.device_name = info.name;
  result.driver = info.driver_info;
  result.limits = info.limits;
  result.fma = info.fma;  // is_lavapipe && lavapipe_fuses_on_this_host()
  result.width = width_;
  result.height = height_;
  result.samples = samples_;
  result.depth_format = depth_format_;
  const size_t count = size_t(width_) * height_ * samples_;
  result.owner.resize(count);
  std::memcpy(result.owner.data(), read_back_.owner.mapped, count * sizeof(uint32_t));
  if (read_back_.depth_gather) {  // multisampled: the sampled floats' bits, one per sample
    const auto* sampled = static_cast<const uint32_t*>(read_back_.depth->mapped);
    result.depth_raw.resize(count);
    const UnormSampling sampling = depth_sampling_.value_or(UnormSampling::Quotient);  // D32: unused
    for (size_t i = 0; i < count; ++i)
      result.depth_raw[i] = depth_raw_from_sampled(depth_format_, sampling, sampled[i]);
  } else if (read_back_.depth) {  // single sample: the depth-aspect copy
    const auto* texels = static_cast<const unsigned char*>(read_back_.depth->mapped);
    const uint32_t texel_bytes = depth_copy_texel_bytes(depth_format_);
    result.depth_raw.resize(count);
    for (size_t i = 0; i < count; ++i)
      result.depth_raw[i] = depth_raw_from_copy(depth_format_, texels + i * texel_bytes);
  }
  return result;
}

}  // namespace rastercmp::vk
