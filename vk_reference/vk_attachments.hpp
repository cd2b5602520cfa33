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
  bool depth_sampled = false;  // multisampled depth the depth gather can read (SAMPLED usage)
  Owned<VkFramebuffer> framebuffer;
};

// Single-sample images are copied out (transfer source); multisampled images are read by the
// gather compute shaders (sampled): always the owner, depth where `sampled_depth`.
ImageSpec owner_image_spec(const AttachmentConfig& config, uint32_t width, uint32_t height);
ImageSpec depth_image_spec(const AttachmentConfig& config, uint32_t width, uint32_t height, bool sampled_depth);

// Whether a multisampled depth attachment of `config` can also be sampled (the format's optimal
// tiling features include SAMPLED_IMAGE and the image, with SAMPLED usage, supports the sample
// count and size). False for single-sample configs and DepthFormat::None. Where false, the
// multisampled depth is not read back and the render carries no depth ("depth not compared").
bool multisampled_depth_readable(const Context& context, const AttachmentConfig& config, uint32_t width,
                                 uint32_t height);

// Throws NotSupportedError naming what the device lacks for these attachments.
void require_attachment_support(const Context& context, const AttachmentConfig& config, uint32_t width,
                                uint32_t height);

Attachments create_attachments(const Context& context, VkRenderPass render_pass, const AttachmentConfig& config,
                               uint32_t width, uint32_t height, bool sampled_depth);

}  // namespace rastercmp::vk
