#include "vk_reference/vk_pipeline_state.hpp"

#include "vk_reference/vk_translate.hpp"

namespace rastercmp::vk {

void fill_rasterization(const RasterState& state, RasterizationChain& chain) {
  VkPipelineRasterizationStateCreateInfo& r = chain.rasterization;
  r = VkPipelineRasterizationStateCreateInfo{};
  r.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  r.depthClampEnable = state.depth_clamp;
  r.rasterizerDiscardEnable = VK_FALSE;
  r.polygonMode = to_vk(state.polygon_mode);
  r.cullMode = to_vk(state.cull_mode);
  r.frontFace = to_vk(state.front_face);
  r.depthBiasEnable = state.depth_bias.enable;
  // The factors are dynamic state (SharedStates): vkCmdSetDepthBias sets them per draw (vk_record.cpp).
  r.lineWidth = state.line_width;

  const void** tail = &r.pNext;
  if (state.line_mode != LineMode::Default) {
    chain.line = VkPipelineRasterizationLineStateCreateInfoEXT{};
    chain.line.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT;
    chain.line.lineRasterizationMode = to_vk(state.line_mode);
    chain.line.stippledLineEnable = VK_FALSE;
    *tail = &chain.line;
    tail = &chain.line.pNext;
  }
  if (state.depth_clip.has_value()) {
    chain.depth_clip = VkPipelineRasterizationDepthClipStateCreateInfoEXT{};
    chain.depth_clip.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_DEPTH_CLIP_STATE_CREATE_INFO_EXT;
    chain.depth_clip.depthClipEnable = *state.depth_clip;
    *tail = &chain.depth_clip;
  }
}

SharedStates::SharedStates() {
  vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  vertex_input.vertexBindingDescriptionCount = 1;
  vertex_input.pVertexBindingDescriptions = &binding;
  vertex_input.vertexAttributeDescriptionCount = 1;
  vertex_input.pVertexAttributeDescriptions = &pos_clip;
  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dynamic.dynamicStateCount = 3;
  dynamic.pDynamicStates = dynamic_states;
  owner_blend.blendEnable = VK_FALSE;
  owner_blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT;  // R32_UINT has one component
  blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  blend.attachmentCount = 1;
  blend.pAttachments = &owner_blend;
}

VkPipelineMultisampleStateCreateInfo multisample_state(uint32_t samples) {
  VkPipelineMultisampleStateCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  info.rasterizationSamples = to_vk_samples(samples);
  info.sampleShadingEnable = VK_FALSE;  // one owner per fragment, written to its covered samples
  return info;
}

VkPipelineDepthStencilStateCreateInfo depth_stencil_state(const DepthState& depth) {
  VkPipelineDepthStencilStateCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  info.depthTestEnable = depth.test_enable;
  info.depthWriteEnable = depth.write_enable;
  info.depthCompareOp = to_vk(depth.compare_op);
  info.depthBoundsTestEnable = VK_FALSE;
  info.stencilTestEnable = VK_FALSE;
  info.minDepthBounds = 0.0f;
  info.maxDepthBounds = 1.0f;
  return info;
}

VkPipelineInputAssemblyStateCreateInfo input_assembly_state(Topology topology) {
  VkPipelineInputAssemblyStateCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  info.topology = to_vk(topology);
  info.primitiveRestartEnable = VK_FALSE;
  return info;
}

bool draws_points(Topology topology, const RasterState& state) {
  return topology == Topology::PointList ||
         (is_triangle_topology(topology) && state.polygon_mode == PolygonMode::Point);
}

}  // namespace rastercmp::vk
