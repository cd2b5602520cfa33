// Render passes and graphics pipelines, created on first use and cached for the renderer's
// life: one render pass per attachment configuration, one pipeline per distinct
// (attachment configuration, topology, RasterState). Viewport and scissor are dynamic state,
// so a pipeline serves every scene with the same raster state.
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
  explicit PipelineCache(const Context& context);

  VkRenderPass render_pass(const AttachmentConfig& config);
  VkPipeline graphics_pipeline(const AttachmentConfig& config, Topology topology, const RasterState& state);
  // Push constant: the draw index (uint32, fragment stage) for the owner id.
  VkPipelineLayout graphics_layout() const { return layout_.get(); }

 private:
  const Context& context_;
  Owned<VkShaderModule> vertex_;         // passthrough.vert
  Owned<VkShaderModule> vertex_points_;  // passthrough_points.vert (writes gl_PointSize)
  Owned<VkShaderModule> fragment_;       // owner.frag
  Owned<VkPipelineLayout> layout_;
  std::map<AttachmentConfig, Owned<VkRenderPass>> render_passes_;
  std::map<PipelineKey, Owned<VkPipeline>> pipelines_;
};

// A shader module from embedded SPIR-V words.
Owned<VkShaderModule> create_shader_module(VkDevice device, const uint32_t* code, size_t size_bytes);

}  // namespace rastercmp::vk
