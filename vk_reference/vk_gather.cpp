#include "vk_reference/vk_gather.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>

#include <fmt/core.h>

#include "model/errors.hpp"
#include "shaders/gather_depth_ms_comp.h"
#include "shaders/gather_owner_ms_comp.h"
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
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, band_count},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, band_count}};
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = band_count;
  pool_info.poolSizeCount = 2;
  pool_info.pPoolSizes = sizes;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(api().vkCreateDescriptorPool(device, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
  Binding binding;
  binding.pool = own(device, api().vkDestroyDescriptorPool, pool);
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

}  // namespace rastercmp::vk
