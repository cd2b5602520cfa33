#include "vk_reference/vk_resources.hpp"

#include <fmt/core.h>

#include "model/errors.hpp"
#include "vk_reference/vk_check.hpp"
#include "vk_reference/vk_loader.hpp"

namespace rastercmp::vk {
namespace {

Owned<VkDeviceMemory> allocate(const Context& context, const VkMemoryRequirements& requirements,
                               VkMemoryPropertyFlags properties) {
  VkMemoryAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = context.memory_type(requirements.memoryTypeBits, properties);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  check(api().vkAllocateMemory(context.device(), &info, nullptr, &memory), "vkAllocateMemory");
  return own(context.device(), api().vkFreeMemory, memory);
}

}  // namespace

Buffer create_host_buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage) {
  const VkDevice device = context.device();
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer handle = VK_NULL_HANDLE;
  check(api().vkCreateBuffer(device, &info, nullptr, &handle), "vkCreateBuffer");
  Buffer buffer;
  buffer.buffer = own(device, api().vkDestroyBuffer, handle);
  buffer.size = size;
  VkMemoryRequirements requirements{};
  api().vkGetBufferMemoryRequirements(device, handle, &requirements);
  // Coherent memory: host writes before vkQueueSubmit and reads after the fence need no
  // flush or invalidate. Every device has such a type (Vulkan spec, "Memory Types").
  buffer.memory =
      allocate(context, requirements, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  check(api().vkBindBufferMemory(device, handle, buffer.memory.get(), 0), "vkBindBufferMemory");
  check(api().vkMapMemory(device, buffer.memory.get(), 0, VK_WHOLE_SIZE, 0, &buffer.mapped), "vkMapMemory");
  return buffer;
}

Image create_image(const Context& context, const ImageSpec& spec) {
  const VkDevice device = context.device();
  VkImageCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = spec.format;
  info.extent = {spec.width, spec.height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = spec.samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = spec.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage handle = VK_NULL_HANDLE;
  check(api().vkCreateImage(device, &info, nullptr, &handle), "vkCreateImage");
  Image image;
  image.image = own(device, api().vkDestroyImage, handle);
  image.format = spec.format;
  VkMemoryRequirements requirements{};
  api().vkGetImageMemoryRequirements(device, handle, &requirements);
  image.memory = allocate(context, requirements, 0);
  check(api().vkBindImageMemory(device, handle, image.memory.get(), 0), "vkBindImageMemory");

  VkImageViewCreateInfo view_info{};
  view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  view_info.image = handle;
  view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view_info.format = spec.format;
  view_info.subresourceRange = {spec.aspect, 0, 1, 0, 1};
  VkImageView view = VK_NULL_HANDLE;
  check(api().vkCreateImageView(device, &view_info, nullptr, &view), "vkCreateImageView");
  image.view = own(device, api().vkDestroyImageView, view);
  return image;
}

void require_image_support(const Context& context, const ImageSpec& spec, const std::string& role) {
  VkImageFormatProperties properties{};
  const VkResult result = api().vkGetPhysicalDeviceImageFormatProperties(
      context.physical_device(), spec.format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, spec.usage, 0, &properties);
  const std::string what = fmt::format("{} on {} (usage {:#x})", role, context.info().name, spec.usage);
  if (result == VK_ERROR_FORMAT_NOT_SUPPORTED) throw NotSupportedError(what + " is not supported");
  check(result, "vkGetPhysicalDeviceImageFormatProperties");
  if (!(properties.sampleCounts & spec.samples)) {
    throw NotSupportedError(fmt::format("{} does not support {} samples", what, static_cast<int>(spec.samples)));
  }
  if (spec.width > properties.maxExtent.width || spec.height > properties.maxExtent.height) {
    throw NotSupportedError(
        fmt::format("{} is limited to {}x{}", what, properties.maxExtent.width, properties.maxExtent.height));
  }
}

Owned<VkCommandBuffer> allocate_commands(const Context& context) {
  VkCommandBufferAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  info.commandPool = context.command_pool();
  info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  info.commandBufferCount = 1;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  check(api().vkAllocateCommandBuffers(context.device(), &info, &commands), "vkAllocateCommandBuffers");
  const VkDevice device = context.device();
  const VkCommandPool pool = context.command_pool();
  return Owned<VkCommandBuffer>(commands,
                                [device, pool](VkCommandBuffer h) { api().vkFreeCommandBuffers(device, pool, 1, &h); });
}

Owned<VkFence> create_fence(const Context& context) {
  VkFenceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  VkFence fence = VK_NULL_HANDLE;
  check(api().vkCreateFence(context.device(), &info, nullptr, &fence), "vkCreateFence");
  return own(context.device(), api().vkDestroyFence, fence);
}

void submit_and_wait(const Context& context, VkCommandBuffer commands, VkFence fence) {
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  check(api().vkQueueSubmit(context.queue(), 1, &submit, fence), "vkQueueSubmit");
  check(api().vkWaitForFences(context.device(), 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

VkImageMemoryBarrier layout_barrier(VkImage image, VkImageAspectFlags aspect, VkAccessFlags src_access,
                                    VkImageLayout old_layout, VkAccessFlags dst_access, VkImageLayout new_layout) {
  VkImageMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  barrier.oldLayout = old_layout;
  barrier.newLayout = new_layout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {aspect, 0, 1, 0, 1};
  return barrier;
}

void host_read_barrier(VkCommandBuffer commands, VkPipelineStageFlags src_stage, VkAccessFlags src_access) {
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  api().vkCmdPipelineBarrier(commands, src_stage, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace rastercmp::vk
