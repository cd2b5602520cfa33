// Buffers and images with their own memory. lavapipe has one memory type, device-local and
// host-visible; on other devices buffers take a host-visible coherent type, images any type.
#pragma once

#include <string>

#include <vulkan/vulkan.h>

#include "vk_reference/vk_context.hpp"
#include "vk_reference/vk_handle.hpp"

namespace rastercmp::vk {

// A host-visible, host-coherent buffer, mapped for its whole life.
struct Buffer {
  Owned<VkDeviceMemory> memory;  // declared first: freed after the buffer is destroyed
  Owned<VkBuffer> buffer;
  VkDeviceSize size = 0;
  void* mapped = nullptr;
};

Buffer create_host_buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage);

// A 2D image with one mip level and layer, its memory and a view of `aspect`.
struct Image {
  Owned<VkDeviceMemory> memory;
  Owned<VkImage> image;
  Owned<VkImageView> view;
  VkFormat format = VK_FORMAT_UNDEFINED;
};

struct ImageSpec {
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkImageUsageFlags usage = 0;
  VkImageAspectFlags aspect = 0;
};

Image create_image(const Context& context, const ImageSpec& spec);

// Throws NotSupportedError naming what the device lacks for an image of `spec`.
void require_image_support(const Context& context, const ImageSpec& spec, const std::string& role);

// A primary command buffer from the context's pool, and an unsignalled fence.
Owned<VkCommandBuffer> allocate_commands(const Context& context);
Owned<VkFence> create_fence(const Context& context);
// Submits `commands` to the context's queue with the unsignalled `fence` and waits for it.
void submit_and_wait(const Context& context, VkCommandBuffer commands, VkFence fence);

// A layout transition of the image's one level and layer.
VkImageMemoryBarrier layout_barrier(VkImage image, VkImageAspectFlags aspect, VkAccessFlags src_access,
                                    VkImageLayout old_layout, VkAccessFlags dst_access, VkImageLayout new_layout);
// Makes the writes of `src_stage` with `src_access` visible to the host's reads.
void host_read_barrier(VkCommandBuffer commands, VkPipelineStageFlags src_stage, VkAccessFlags src_access);

}  // namespace rastercmp::vk
