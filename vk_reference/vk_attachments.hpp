// The scene's render targets: the R32_UINT owner attachment and the optional depth attachment,
// both with the scene's sample count, and the framebuffer over them.
#pragma once

#include <optional>

#include <vulkan/vulkan.h>

#include "vk_reference/vk_context.hpp"
#include "vk_reference/vk_pipeline.hpp"
#include "vk_reference/vk_resources.hpp"

namespace rastercmp::vk {

struct Attachments {
  Image owner;
  std::optional<Image> depth;  // absent for DepthFormat::None
  Owned<VkFramebuffer> framebuffer;
};

// Single-sample images are copied out (transfer source); the multisampled owner image is read by
// the gather compute shader (sampled). Multisampled depth is not read back.
ImageSpec owner_image_spec(const AttachmentConfig& config, uint32_t width, uint32_t height);
ImageSpec depth_image_spec(const AttachmentConfig& config, uint32_t width, uint32_t height);

// Throws NotSupportedError naming what the device lacks for these attachments.
void require_attachment_support(const Context& context, const AttachmentConfig& config, uint32_t width,
                                uint32_t height);

Attachments create_attachments(const Context& context, VkRenderPass render_pass, const AttachmentConfig& config,
                               uint32_t width, uint32_t height);

}  // namespace rastercmp::vk
