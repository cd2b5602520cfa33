// RasterState → the fixed-function create-info structs of a graphics pipeline. The one place
// where the scene's raster state is translated to Vulkan (the one place that speaks both).
#pragma once

#include <vulkan/vulkan.h>

#include "model/scene.hpp"

namespace rastercmp::vk {

// The rasterization state with its optional extension structs. Pointers inside point into the
// object itself: fill it in place and do not copy it.
struct RasterizationChain {
  VkPipelineRasterizationStateCreateInfo rasterization{};
  VkPipelineRasterizationLineStateCreateInfoEXT line{};
  VkPipelineRasterizationDepthClipStateCreateInfoEXT depth_clip{};

  RasterizationChain() = default;
  RasterizationChain(const RasterizationChain&) = delete;
  RasterizationChain& operator=(const RasterizationChain&) = delete;
};

// VK_EXT_line_rasterization is chained only when line_mode != Default, VK_EXT_depth_clip_enable
// only when state.depth_clip has a value (docs/lavapipe-rules.md §1.2: without it, depth clip
// is !depthClampEnable). The provoking vertex stays FIRST (Test configuration §1).
void fill_rasterization(const RasterState& state, RasterizationChain& chain);

// The states every graphics pipeline shares: one vec4 clip position per vertex, viewport and
// scissor as dynamic state (set per scene at record time), the depth bias factors as dynamic state
// (set per draw, so draws that differ only in their factors share one pipeline and lavapipe
// compiles its shaders once), and the owner attachment written without blending. Pointers inside point into the object itself: do not copy it.
struct SharedStates {
  VkVertexInputBindingDescription binding{0, 4 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription pos_clip{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0};
  VkPipelineVertexInputStateCreateInfo vertex_input{};
  VkPipelineViewportStateCreateInfo viewport{};
  VkDynamicState dynamic_states[3] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                     VK_DYNAMIC_STATE_DEPTH_BIAS};
  VkPipelineDynamicStateCreateInfo dynamic{};
  VkPipelineColorBlendAttachmentState owner_blend{};
  VkPipelineColorBlendStateCreateInfo blend{};

  SharedStates();
  SharedStates(const SharedStates&) = delete;
  SharedStates& operator=(const SharedStates&) = delete;
};

VkPipelineMultisampleStateCreateInfo multisample_state(uint32_t samples);

VkPipelineDepthStencilStateCreateInfo depth_stencil_state(const DepthState& depth);

VkPipelineInputAssemblyStateCreateInfo input_assembly_state(Topology topology);

// Point primitives (point_list, or polygon mode point) need a vertex shader writing gl_PointSize.
bool draws_points(Topology topology, const RasterState& state);

}  // namespace rastercmp::vk
