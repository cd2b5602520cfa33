// Render passes and graphics pipelines, created on first use and cached: one render pass per
// attachment configuration (for the renderer's life), one pipeline per distinct (attachment
// configuration, topology, RasterState). Viewport and scissor are dynamic state, so a pipeline
// serves every scene with the same raster state.
//
// The pipeline cache is bounded. A soak meets a new key in most line scenes (the width is baked
// in), and every pipeline holds the driver's compiled code. Unbounded, `soak --seed 1` grew by
// about 45 MB of resident memory a second on lavapipe 22.3.6; on 26.2.6 the process's memory
// mappings grew by about 6,500 a second and reached the kernel's 65,530 (vm.max_map_count) within
// a minute, where LLVM aborted ("Unable to allocate section memory"). Bounded, the same soak holds
// at about 300 MB and 1,300 mappings. Pipelines are evicted,
// least recently used first, only between frames: while a Frame is alive (PipelineCache::Pin)
// nothing it recorded can be destroyed.
#pragma once

#include <compare>
#include <cstdint>
#include <map>

#include <vulkan/vulkan.h>

#include "model/scene.hpp"
#include "vk_reference/vk_context.hpp"
#include "vk_reference/vk_handle.hpp"

namespace rastercmp::vk {

// What a render pass (and every pipeline used in it) depends on.
struct AttachmentConfig {
  DepthFormat depth_format = DepthFormat::None;
  uint32_t samples = 1;
  auto operator<=>(const AttachmentConfig&) const = default;
};

// Everything a graphics pipeline bakes in. Floats are kept by bit pattern so keys order totally.
struct PipelineKey {
  AttachmentConfig attachments;
  Topology topology = Topology::TriangleList;
  CullMode cull_mode = CullMode::None;
  FrontFace front_face = FrontFace::CounterClockwise;
  PolygonMode polygon_mode = PolygonMode::Fill;
  LineMode line_mode = LineMode::Default;
  uint32_t line_width_bits = 0;
  bool depth_test = false, depth_write = false;
  CompareOp compare_op = CompareOp::Less;
  bool bias_enable = false;  // the factors are dynamic state, set per draw
  bool depth_clamp = false;
  int depth_clip = -1;  // -1: VK_EXT_depth_clip_enable not chained; else its depthClipEnable
  auto operator<=>(const PipelineKey&) const = default;
};

PipelineKey make_pipeline_key(const AttachmentConfig& attachments, Topology topology, const RasterState& state);

// Throws NotSupportedError naming the feature or extension `state` needs and the device lacks.
void require_state_support(const Context& context, Topology topology, const RasterState& state);

class PipelineCache {
 public:
  // Holds at most max_pipelines between frames (trim()); at least 2.
  PipelineCache(const Context& context, size_t max_pipelines);

  VkRenderPass render_pass(const AttachmentConfig& config);
  VkPipeline graphics_pipeline(const AttachmentConfig& config, Topology topology, const RasterState& state);

  // Held by each Frame for its life: trim() evicts nothing while a pin is held.
  class Pin {
   public:
    explicit Pin(PipelineCache& cache) : cache_(&cache) { ++cache_->pins_; }
    ~Pin() { --cache_->pins_; }
    Pin(const Pin&) = delete;
    Pin& operator=(const Pin&) = delete;

   private:
    PipelineCache* cache_;
  };

  // When the cache holds more than its maximum and no Frame is alive, evicts the least recently
  // used pipelines down to half the maximum. Returns how many were destroyed.
  size_t trim();
  size_t pipeline_count() const { return pipelines_.size(); }
  // Push constant: the draw index (uint32, fragment stage) for the owner id.
  VkPipelineLayout graphics_layout() const { return layout_.get(); }

 private:
  const Context& context_;
  size_t max_pipelines_;
  Owned<VkShaderModule> vertex_;         // passthrough.vert
  Owned<VkShaderModule> vertex_points_;  // passthrough_points.vert (writes gl_PointSize)
  Owned<VkShaderModule> fragment_;       // owner.frag
  Owned<VkPipelineLayout> layout_;
  std::map<AttachmentConfig, Owned<VkRenderPass>> render_passes_;
  struct CachedPipeline {
    Owned<VkPipeline> pipeline;
    uint64_t last_use = 0;  // use_clock_ at the last lookup
  };
  std::map<PipelineKey, CachedPipeline> pipelines_;
  uint64_t use_clock_ = 0;
  int pins_ = 0;
};

// A shader module from embedded SPIR-V words.
Owned<VkShaderModule> create_shader_module(VkDevice device, const uint32_t* code, size_t size_bytes);

}  // namespace rastercmp::vk
