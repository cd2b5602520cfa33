// Command recording for one frame: clear, draw every Draw in order, then copy the results out.
#include <vector>

#include "vk_reference/vk_frame.hpp"
#include "vk_reference/vk_loader.hpp"
#include "vk_reference/vk_translate.hpp"

namespace rastercmp::vk {
namespace {

void begin_render_pass(VkCommandBuffer commands, const Scene& scene, VkRenderPass render_pass,
                       const Attachments& attachments) {
  VkClearValue clears[2] = {};
  clears[0].color.uint32[0] = kOwnerBackground;
  clears[1].depthStencil = {scene.depth_clear, 0};
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = render_pass;
  begin.framebuffer = attachments.framebuffer.get();
  // renderArea = the whole framebuffer: lavapipe does not scissor draws by it (docs/lavapipe-rules.md §2.5).
  begin.renderArea = {{0, 0}, {scene.width, scene.height}};
  begin.clearValueCount = attachments.depth ? 2 : 1;
  begin.pClearValues = clears;
  api().vkCmdBeginRenderPass(commands, &begin, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport = to_vk(scene.effective_viewport());
  const VkRect2D scissor = to_vk_scissor(scene.effective_scissor());
  api().vkCmdSetViewport(commands, 0, 1, &viewport);
  api().vkCmdSetScissor(commands, 0, 1, &scissor);
}

// One vkCmdDraw / vkCmdDrawIndexed per Draw; the draw index reaches owner.frag as a push constant.
void record_draws(VkCommandBuffer commands, VkPipelineLayout layout, const Geometry& geometry) {
  VkPipeline bound = VK_NULL_HANDLE;
  const VkBuffer vertices = geometry.vertices.buffer.get();
  for (uint32_t draw_index = 0; draw_index < geometry.calls.size(); ++draw_index) {
    const DrawCall& call = geometry.calls[draw_index];
    if (call.vertex_count == 0) continue;
    if (call.pipeline != bound) {
      api().vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, call.pipeline);
      bound = call.pipeline;
    }
    // Dynamic state (SharedStates): every pipeline takes its factors from here; a draw without
    // bias has depthBiasEnable off in its pipeline, which makes them unused.
    api().vkCmdSetDepthBias(commands, call.depth_bias.constant_factor, call.depth_bias.clamp,
                            call.depth_bias.slope_factor);
    api().vkCmdPushConstants(commands, layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof draw_index, &draw_index);
    api().vkCmdBindVertexBuffers(commands, 0, 1, &vertices, &call.vertex_offset);
    if (call.indexed) {
      api().vkCmdBindIndexBuffer(commands, geometry.indices->buffer.get(), call.index_offset, VK_INDEX_TYPE_UINT32);
      api().vkCmdDrawIndexed(commands, call.vertex_count, 1, 0, 0, 0);
    } else {
      api().vkCmdDraw(commands, call.vertex_count, 1, 0, 0);
    }
  }
}

VkBufferImageCopy whole_image(const Scene& scene, VkImageAspectFlags aspect) {
  VkBufferImageCopy region{};
  region.bufferOffset = 0;
  region.bufferRowLength = 0;  // tightly packed
  region.bufferImageHeight = 0;
  region.imageSubresource = {aspect, 0, 0, 1};
  region.imageExtent = {scene.width, scene.height, 1};
  return region;
}

// Single sample: owner and the depth aspect copied to buffers as they are stored.
void record_copies(VkCommandBuffer commands, const Scene& scene, const Attachments& attachments,
                   const ReadBack& read_back) {
  std::vector<VkImageMemoryBarrier> barriers = {layout_barrier(
      attachments.owner.image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)};
  if (attachments.depth) {
    barriers.push_back(layout_barrier(attachments.depth->image.get(), VK_IMAGE_ASPECT_DEPTH_BIT,
                                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                                      VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_ACCESS_TRANSFER_READ_BIT,
                                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
  }
  const VkPipelineStageFlags attachment_stages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                 VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                 VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  api().vkCmdPipelineBarrier(commands, attachment_stages, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                             static_cast<uint32_t>(barriers.size()), barriers.data());
  const VkBufferImageCopy owner_region = whole_image(scene, VK_IMAGE_ASPECT_COLOR_BIT);
  api().vkCmdCopyImageToBuffer(commands, attachments.owner.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               read_back.owner.buffer.get(), 1, &owner_region);
  if (attachments.depth) {
    const VkBufferImageCopy depth_region = whole_image(scene, VK_IMAGE_ASPECT_DEPTH_BIT);
    api().vkCmdCopyImageToBuffer(commands, attachments.depth->image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                 read_back.depth->buffer.get(), 1, &depth_region);
  }
  host_read_barrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
}

// Multisampled: the owner samples, and the depth samples where the device can sample the depth
// attachment, gathered by compute shaders.
void record_gather(VkCommandBuffer commands, const Attachments& attachments, const ReadBack& read_back,
                   const Gathers& gathers) {
  std::vector<VkImageMemoryBarrier> barriers = {layout_barrier(
      attachments.owner.image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ACCESS_SHADER_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)};
  VkPipelineStageFlags src_stages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  if (read_back.depth_gather) {
    barriers.push_back(layout_barrier(attachments.depth->image.get(), VK_IMAGE_ASPECT_DEPTH_BIT,
                                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                                      VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_ACCESS_SHADER_READ_BIT,
                                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
    src_stages |= VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  }
  api().vkCmdPipelineBarrier(commands, src_stages, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr,
                             static_cast<uint32_t>(barriers.size()), barriers.data());
  gathers.owner->record(commands, *read_back.gather);
  if (read_back.depth_gather) gathers.depth->record(commands, *read_back.depth_gather);
  host_read_barrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
}

}  // namespace

void record_frame(VkCommandBuffer commands, const Scene& scene, VkRenderPass render_pass, VkPipelineLayout layout,
                  const Attachments& attachments, const Geometry& geometry, const ReadBack& read_back,
                  const Gathers& gathers) {
  begin_render_pass(commands, scene, render_pass, attachments);
  record_draws(commands, layout, geometry);
  api().vkCmdEndRenderPass(commands);
  if (read_back.gather) {
    record_gather(commands, attachments, read_back, gathers);
  } else {
    record_copies(commands, scene, attachments, read_back);
  }
}

}  // namespace rastercmp::vk
