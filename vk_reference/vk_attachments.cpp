#include "vk_reference/vk_attachments.hpp"

#include <string>

#include <fmt/core.h>

#include "model/errors.hpp"
#include "vk_reference/vk_check.hpp"
#include "vk_reference/vk_loader.hpp"
#include "vk_reference/vk_translate.hpp"

namespace rastercmp::vk {

ImageSpec owner_image_spec(const AttachmentConfig& config, uint32_t width, uint32_t height) {
  ImageSpec spec{kOwnerFormat,
                 width,
                 height,
                 to_vk_samples(config.samples),
                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                 VK_IMAGE_ASPECT_COLOR_BIT};
  spec.usage |= config.samples == 1 ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : VK_IMAGE_USAGE_SAMPLED_BIT;
  return spec;
}

ImageSpec depth_image_spec(const AttachmentConfig& config, uint32_t width, uint32_t height, bool sampled_depth) {
  ImageSpec spec{to_vk_format(config.depth_format),
                 width,
                 height,
                 to_vk_samples(config.samples),
                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                 VK_IMAGE_ASPECT_DEPTH_BIT};
  if (config.samples == 1) spec.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (config.samples > 1 && sampled_depth) spec.usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
  return spec;
}

bool multisampled_depth_readable(const Context& context, const AttachmentConfig& config, uint32_t width,
                                 uint32_t height) {
  if (config.samples == 1 || config.depth_format == DepthFormat::None) return false;
  VkFormatProperties features{};
  api().vkGetPhysicalDeviceFormatProperties(context.physical_device(), to_vk_format(config.depth_format), &features);
  if (!(features.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)) return false;
  try {
    require_image_support(context, depth_image_spec(config, width, height, /*sampled_depth=*/true), "sampled depth");
  } catch (const NotSupportedError&) {
    return false;
  }
  return true;
}

void require_attachment_support(const Context& context, const AttachmentConfig& config, uint32_t width,
                                uint32_t height) {
  const VkPhysicalDeviceLimits& limits = context.enabled().limits;
  if (width > limits.maxFramebufferWidth || height > limits.maxFramebufferHeight) {
    throw NotSupportedError(fmt::format("{} limits framebuffers to {}x{}; the scene is {}x{}", context.info().name,
                                        limits.maxFramebufferWidth, limits.maxFramebufferHeight, width, height));
  }
  require_image_support(context, owner_image_spec(config, width, height),
                        fmt::format("an R32_UINT owner attachment with {} samples", config.samples));
  if (config.depth_format == DepthFormat::None) return;
  require_image_support(
      context, depth_image_spec(config, width, height, /*sampled_depth=*/false),
      fmt::format("a {} depth attachment with {} samples", to_string(config.depth_format), config.samples));
}

Attachments create_attachments(const Context& context, VkRenderPass render_pass, const AttachmentConfig& config,
                               uint32_t width, uint32_t height, bool sampled_depth) {
  Attachments attachments;
  attachments.owner = create_image(context, owner_image_spec(config, width, height));
  VkImageView views[2] = {attachments.owner.view.get(), VK_NULL_HANDLE};
  if (config.depth_format != DepthFormat::None) {
    attachments.depth = create_image(context, depth_image_spec(config, width, height, sampled_depth));
    attachments.depth_sampled = config.samples > 1 && sampled_depth;
    views[1] = attachments.depth->view.get();
  }
  VkFramebufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  info.renderPass = render_pass;
  info.attachmentCount = attachments.depth ? 2 : 1;
  info.pAttachments = views;
  info.width = width;
  info.height = height;
  info.layers = 1;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  check(api().vkCreateFramebuffer(context.device(), &info, nullptr, &framebuffer), "vkCreateFramebuffer");
  attachments.framebuffer = own(context.device(), api().vkDestroyFramebuffer, framebuffer);
  return attachments;
}

}  // namespace rastercmp::vk
