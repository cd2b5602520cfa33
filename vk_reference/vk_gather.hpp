// Reads a multisampled attachment sample by sample: a compute shader texelFetches each sample
// into a storage buffer laid out as (y * width + x) * samples + sample, the RenderResult layout.
// Owner: shaders/gather_owner_ms.comp reads a usampler2DMS (the owner ids themselves). Depth:
// shaders/gather_depth_ms.comp reads a sampler2DMS and stores the sampled float's bits (the host
// recovers the raw stored bits, vk_translate.hpp depth_raw_from_sampled). The buffer is bound in
// bands of whole rows, each within maxStorageBufferRange and offset-aligned.
#pragma once

#include <optional>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk_reference/vk_context.hpp"
#include "vk_reference/vk_handle.hpp"
#include "vk_reference/vk_resources.hpp"
#include "vk_reference/vk_translate.hpp"

namespace rastercmp::vk {

enum class GatherKind { Owner, Depth };

class SampleGather {
 public:
  SampleGather(const Context& context, GatherKind kind);

  struct Band {
    VkDescriptorSet set = VK_NULL_HANDLE;
    uint32_t first_row = 0, rows = 0;
  };
  // The descriptors of one scene: its image (a view of the colour or depth aspect, in
  // SHADER_READ_ONLY_OPTIMAL) and output buffer of width * height * samples uint32.
  struct Binding {
    Owned<VkDescriptorPool> pool;  // owns the sets
    std::vector<Band> bands;
    uint32_t width = 0, samples = 0;
  };
  // Throws NotSupportedError if a single row exceeds the device's storage-buffer range.
  Binding bind(VkImageView image_ms, const Buffer& samples_out, uint32_t width, uint32_t height,
               uint32_t samples) const;

  // Records the dispatches; the caller places the barriers around them.
  void record(VkCommandBuffer commands, const Binding& binding) const;

 private:
  const Context& context_;
  GatherKind kind_;
  Owned<VkSampler> sampler_;
  Owned<VkDescriptorSetLayout> set_layout_;
  Owned<VkPipelineLayout> layout_;
  Owned<VkShaderModule> shader_;
  Owned<VkPipeline> pipeline_;
};

// How the device converts the UNORM depth `format` to the float its shaders sample, measured:
// 256x256 known raw values (D16: every value; X8_D24: values over the whole range with varied low
// bits, and the lowest and highest 16) copied into a single-sample image and sampled by
// shaders/sample_depth.comp, each float compared with every kUnormSamplings conversion. The first
// conversion that gives every float; none if no conversion does or the device cannot sample or
// fill such an image (the multisampled depth of that format is then not read back). Submits and
// waits.
std::optional<UnormSampling> measure_unorm_sampling(const Context& context, DepthFormat format);

}  // namespace rastercmp::vk
