#include "vk_reference/vk_gather.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "model/errors.hpp"
#include "shaders/gather_depth_ms_comp.h"
#include "shaders/gather_owner_ms_comp.h"
#include "shaders/sample_depth_comp.h"
#include "vk_reference/vk_check.hpp"
#include "vk_reference/vk_loader.hpp"
#include "vk_reference/vk_pipeline.hpp"

namespace rastercmp::vk {
namespace {

constexpr uint32_t kLocalSize = 8;  // gather_{owner,depth}_ms.comp local_size_x/y

struct GatherConstants {
  uint32_t width, samples, first_row, rows;
};

// Rows per band: as many as fit maxStorageBufferRange, a multiple of the rows that keep each
// band's byte offset aligned to minStorageBufferOffsetAlignment.
uint32_t rows_per_band(const VkPhysicalDeviceLimits& limits, uint64_t row_bytes, const std::string& device,
                       const char* what) {
  const uint64_t align = std::max<uint64_t>(limits.minStorageBufferOffsetAlignment, 1);
  const uint64_t row_step = align / std::gcd(align, row_bytes);
  const uint64_t fit = limits.maxStorageBufferRange / row_bytes;
  const uint64_t rows = fit - fit % row_step;
  if (rows == 0) {
    throw NotSupportedError(fmt::format("{}: a row of {} {} bytes exceeds maxStorageBufferRange {}", device, row_bytes,
                                        what, limits.maxStorageBufferRange));
  }
  return static_cast<uint32_t>(std::min<uint64_t>(rows, UINT32_MAX));
}

Owned<VkSampler> create_sampler(VkDevice device) {
  VkSamplerCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.magFilter = VK_FILTER_NEAREST;
  info.minFilter = VK_FILTER_NEAREST;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.maxLod = 0.0f;
  VkSampler sampler = VK_NULL_HANDLE;
  check(api().vkCreateSampler(device, &info, nullptr, &sampler), "vkCreateSampler");
  return own(device, api().vkDestroySampler, sampler);
}

Owned<VkDescriptorSetLayout> create_set_layout(VkDevice device) {
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = 2;
  info.pBindings = bindings;
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  check(api().vkCreateDescriptorSetLayout(device, &info, nullptr, &layout), "vkCreateDescriptorSetLayout");
  return own(device, api().vkDestroyDescriptorSetLayout, layout);
}

Owned<VkPipelineLayout> create_layout(VkDevice device, VkDescriptorSetLayout set_layout) {
  const VkPushConstantRange constants{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GatherConstants)};
  VkPipelineLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  info.setLayoutCount = 1;
  info.pSetLayouts = &set_layout;
  info.pushConstantRangeCount = 1;
  info.pPushConstantRanges = &constants;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  check(api().vkCreatePipelineLayout(device, &info, nullptr, &layout), "vkCreatePipelineLayout");
  return own(device, api().vkDestroyPipelineLayout, layout);
}

Owned<VkPipeline> create_pipeline(VkDevice device, VkPipelineLayout layout, VkShaderModule shader) {
  VkComputePipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = shader;
  info.stage.pName = "main";
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(api().vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
        "vkCreateComputePipelines");
  return own(device, api().vkDestroyPipeline, pipeline);
}

// A pool for `sets` descriptor sets of the gather layout (an image and a buffer each).
Owned<VkDescriptorPool> create_pool(VkDevice device, uint32_t sets) {
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, sets},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, sets}};
  VkDescriptorPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  info.maxSets = sets;
  info.poolSizeCount = 2;
  info.pPoolSizes = sizes;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(api().vkCreateDescriptorPool(device, &info, nullptr, &pool), "vkCreateDescriptorPool");
  return own(device, api().vkDestroyDescriptorPool, pool);
}

VkDescriptorSet allocate_set(VkDevice device, VkDescriptorPool pool, VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  check(api().vkAllocateDescriptorSets(device, &alloc, &set), "vkAllocateDescriptorSets");
  return set;
}

void write_set(VkDevice device, VkDescriptorSet set, const VkDescriptorImageInfo& image,
               const VkDescriptorBufferInfo& buffer) {
  VkWriteDescriptorSet writes[2] = {};
  for (VkWriteDescriptorSet& w : writes) {
    w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w.dstSet = set;
    w.descriptorCount = 1;
  }
  writes[0].dstBinding = 0;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  writes[0].pImageInfo = &image;
  writes[1].dstBinding = 1;
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[1].pBufferInfo = &buffer;
  api().vkUpdateDescriptorSets(device, 2, writes, 0, nullptr);
}

Owned<VkShaderModule> create_gather_shader(VkDevice device, GatherKind kind) {
  return kind == GatherKind::Owner ? create_shader_module(device, gather_owner_ms_comp, sizeof(gather_owner_ms_comp))
                                   : create_shader_module(device, gather_depth_ms_comp, sizeof(gather_depth_ms_comp));
}

}  // namespace

SampleGather::SampleGather(const Context& context, GatherKind kind)
    : context_(context),
      kind_(kind),
      sampler_(create_sampler(context.device())),
      set_layout_(create_set_layout(context.device())),
      layout_(create_layout(context.device(), set_layout_.get())),
      shader_(create_gather_shader(context.device(), kind)),
      pipeline_(create_pipeline(context.device(), layout_.get(), shader_.get())) {}

SampleGather::Binding SampleGather::bind(VkImageView image_ms, const Buffer& samples_out, uint32_t width,
                                         uint32_t height, uint32_t samples) const {
  const VkDevice device = context_.device();
  const uint64_t row_bytes = uint64_t(width) * samples * sizeof(uint32_t);
  const uint32_t band_rows = rows_per_band(context_.enabled().limits, row_bytes, context_.info().name,
                                           kind_ == GatherKind::Owner ? "owner" : "depth");
  const uint32_t band_count = (height + band_rows - 1) / band_rows;
  Binding binding;
  binding.pool = create_pool(device, band_count);
  const VkDescriptorPool pool = binding.pool.get();
  binding.width = width;
  binding.samples = samples;
  for (uint32_t first_row = 0; first_row < height; first_row += band_rows) {
    const uint32_t rows = std::min(band_rows, height - first_row);
    binding.bands.push_back({allocate_set(device, pool, set_layout_.get()), first_row, rows});
    const VkDescriptorImageInfo image{sampler_.get(), image_ms, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkDescriptorBufferInfo buffer{samples_out.buffer.get(), first_row * row_bytes, rows * row_bytes};
    write_set(device, binding.bands.back().set, image, buffer);
  }
  return binding;
}

void SampleGather::record(VkCommandBuffer commands, const Binding& binding) const {
  api().vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  for (const Band& band : binding.bands) {
    const GatherConstants constants{binding.width, binding.samples, band.first_row, band.rows};
    api().vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &band.set, 0, nullptr);
    api().vkCmdPushConstants(commands, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof constants, &constants);
    api().vkCmdDispatch(commands, (binding.width + kLocalSize - 1) / kLocalSize,
                        (band.rows + kLocalSize - 1) / kLocalSize, 1);
  }
}

namespace {

constexpr uint32_t kProbeSide = 256;  // measure_unorm_sampling's image: 65,536 texels

// The raw values measure_unorm_sampling stores, one a texel: every value of a format of at most
// 65,536 values; else the lowest and highest 16 and between them i * 256 plus varied low bits.
std::vector<uint32_t> probe_values(uint32_t max) {
  std::vector<uint32_t> values(kProbeSide * kProbeSide);
  const uint32_t count = uint32_t(values.size());
  for (uint32_t i = 0; i < count; ++i) {
    if (max < count)
      values[i] = std::min(i, max);
    else if (i < 16)
      values[i] = i;
    else if (i >= count - 16)
      values[i] = max - (count - 1 - i);
    else
      values[i] = i * 256 + (i * 97) % 256;
  }
  return values;
}

}  // namespace

std::optional<UnormSampling> measure_unorm_sampling(const Context& context, DepthFormat format) {
  const DepthFormatInfo info = depth_format_info(format);
  if (info.encoding != DepthEncoding::Unorm) return std::nullopt;
  const VkDevice device = context.device();
  VkFormatProperties features{};
  api().vkGetPhysicalDeviceFormatProperties(context.physical_device(), to_vk_format(format), &features);
  const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
  if ((features.optimalTilingFeatures & needed) != needed) return std::nullopt;
  const ImageSpec spec{to_vk_format(format),
                       kProbeSide,
                       kProbeSide,
                       VK_SAMPLE_COUNT_1_BIT,
                       VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                       VK_IMAGE_ASPECT_DEPTH_BIT};
  try {
    require_image_support(context, spec, "a depth image to measure sampling");
  } catch (const NotSupportedError&) {
    return std::nullopt;
  }
  const std::vector<uint32_t> raw = probe_values(info.raw_mask);
  const uint32_t texel_bytes = depth_copy_texel_bytes(format);  // 2 for D16; 4 for X8_D24, the low 24 bits
  const Image image = create_image(context, spec);
  const Buffer upload =
      create_host_buffer(context, VkDeviceSize(raw.size()) * texel_bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  for (size_t i = 0; i < raw.size(); ++i)
    std::memcpy(static_cast<unsigned char*>(upload.mapped) + i * texel_bytes, &raw[i], texel_bytes);  // little-endian
  const Buffer sampled =
      create_host_buffer(context, VkDeviceSize(raw.size()) * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

  const Owned<VkSampler> sampler = create_sampler(device);
  const Owned<VkDescriptorSetLayout> set_layout = create_set_layout(device);
  const Owned<VkPipelineLayout> layout = create_layout(device, set_layout.get());
  const Owned<VkShaderModule> shader = create_shader_module(device, sample_depth_comp, sizeof(sample_depth_comp));
  const Owned<VkPipeline> pipeline = create_pipeline(device, layout.get(), shader.get());
  const Owned<VkDescriptorPool> pool = create_pool(device, 1);
  const VkDescriptorSet set = allocate_set(device, pool.get(), set_layout.get());
  write_set(device, set, {sampler.get(), image.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {sampled.buffer.get(), 0, sampled.size});

  const Owned<VkCommandBuffer> commands = allocate_commands(context);
  const Owned<VkFence> fence = create_fence(context);
  const VkCommandBuffer cb = commands.get();
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(api().vkBeginCommandBuffer(cb, &begin), "vkBeginCommandBuffer");
  const VkImageMemoryBarrier to_transfer =
      layout_barrier(image.image.get(), VK_IMAGE_ASPECT_DEPTH_BIT, 0, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  api().vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &to_transfer);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
  copy.imageExtent = {kProbeSide, kProbeSide, 1};
  api().vkCmdCopyBufferToImage(cb, upload.buffer.get(), image.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &copy);
  const VkImageMemoryBarrier to_sampled = layout_barrier(
      image.image.get(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
      VK_ACCESS_SHADER_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  api().vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &to_sampled);
  api().vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
  api().vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, 1, &set, 0, nullptr);
  const GatherConstants constants{kProbeSide, 1, 0, kProbeSide};
  api().vkCmdPushConstants(cb, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof constants, &constants);
  api().vkCmdDispatch(cb, kProbeSide / kLocalSize, kProbeSide / kLocalSize, 1);
  host_read_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
  check(api().vkEndCommandBuffer(cb), "vkEndCommandBuffer");
  submit_and_wait(context, cb, fence.get());

  const auto* floats = static_cast<const uint32_t*>(sampled.mapped);
  for (const UnormSampling sampling : kUnormSamplings) {
    bool every = true;
    for (size_t i = 0; i < raw.size() && every; ++i)
      every = std::bit_cast<uint32_t>(sampled_unorm(sampling, raw[i], info.raw_mask)) == floats[i];
    if (every) return sampling;
  }
  return std::nullopt;
}

}  // namespace rastercmp::vk
