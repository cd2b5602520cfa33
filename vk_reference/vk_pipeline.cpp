#include "vk_reference/vk_pipeline.hpp"

#include <algorithm>
#include <bit>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "model/errors.hpp"
#include "shaders/owner_frag.h"
#include "shaders/passthrough_points_vert.h"
#include "shaders/passthrough_vert.h"
#include "vk_reference/vk_check.hpp"
#include "vk_reference/vk_loader.hpp"
#include "vk_reference/vk_pipeline_state.hpp"
#include "vk_reference/vk_translate.hpp"

namespace rastercmp::vk {
namespace {

void require(bool present, const Context& context, const std::string& what, const std::string& why) {
  if (!present) throw NotSupportedError(fmt::format("{} lacks {} (needed for {})", context.info().name, what, why));
}

VkAttachmentDescription owner_attachment(VkSampleCountFlagBits samples) {
  VkAttachmentDescription a{};
  a.format = kOwnerFormat;
  a.samples = samples;
  a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // to kOwnerBackground
  a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  a.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;  // read-back barriers transition it
  return a;
}

VkAttachmentDescription depth_attachment(DepthFormat format, VkSampleCountFlagBits samples) {
  VkAttachmentDescription a = owner_attachment(samples);
  a.format = to_vk_format(format);  // cleared to scene.depth_clear
  // Stored: single-sample depth is copied out, multisampled depth read by the depth gather.
  a.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  return a;
}

Owned<VkRenderPass> create_render_pass(VkDevice device, const AttachmentConfig& config) {
  const VkSampleCountFlagBits samples = to_vk_samples(config.samples);
  const bool has_depth = config.depth_format != DepthFormat::None;
  const VkAttachmentDescription attachments[] = {owner_attachment(samples),
                                                 depth_attachment(config.depth_format, samples)};
  const VkAttachmentReference owner_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &owner_ref;
  subpass.pDepthStencilAttachment = has_depth ? &depth_ref : nullptr;
  // A re-submitted command buffer clears images the previous submission's read-back read.
  VkSubpassDependency after_read_back{};
  after_read_back.srcSubpass = VK_SUBPASS_EXTERNAL;
  after_read_back.dstSubpass = 0;
  after_read_back.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  after_read_back.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                 VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  after_read_back.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  VkRenderPassCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  info.attachmentCount = has_depth ? 2 : 1;
  info.pAttachments = attachments;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 1;
  info.pDependencies = &after_read_back;
  VkRenderPass pass = VK_NULL_HANDLE;
  check(api().vkCreateRenderPass(device, &info, nullptr, &pass), "vkCreateRenderPass");
  return own(device, api().vkDestroyRenderPass, pass);
}

Owned<VkPipelineLayout> create_graphics_layout(VkDevice device) {
  const VkPushConstantRange draw_index{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(uint32_t)};
  VkPipelineLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  info.pushConstantRangeCount = 1;
  info.pPushConstantRanges = &draw_index;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  check(api().vkCreatePipelineLayout(device, &info, nullptr, &layout), "vkCreatePipelineLayout");
  return own(device, api().vkDestroyPipelineLayout, layout);
}

VkPipelineShaderStageCreateInfo stage(VkShaderStageFlagBits which, VkShaderModule module) {
  VkPipelineShaderStageCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage = which;
  info.module = module;
  info.pName = "main";
  return info;
}

}  // namespace

Owned<VkShaderModule> create_shader_module(VkDevice device, const uint32_t* code, size_t size_bytes) {
  VkShaderModuleCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  info.codeSize = size_bytes;
  info.pCode = code;
  VkShaderModule module = VK_NULL_HANDLE;
  check(api().vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule");
  return own(device, api().vkDestroyShaderModule, module);
}

PipelineKey make_pipeline_key(const AttachmentConfig& attachments, Topology topology, const RasterState& state) {
  PipelineKey key;
  key.attachments = attachments;
  key.topology = topology;
  key.cull_mode = state.cull_mode;
  key.front_face = state.front_face;
  key.polygon_mode = state.polygon_mode;
  key.line_mode = state.line_mode;
  key.line_width_bits = std::bit_cast<uint32_t>(state.line_width);
  key.depth_test = state.depth.test_enable;
  key.depth_write = state.depth.write_enable;
  key.compare_op = state.depth.compare_op;
  key.bias_enable = state.depth_bias.enable;
  key.depth_clamp = state.depth_clamp;
  key.depth_clip = state.depth_clip.has_value() ? int(*state.depth_clip) : -1;
  return key;
}

void require_state_support(const Context& context, Topology topology, const RasterState& state) {
  const DeviceCapabilities& caps = context.enabled();
  if (state.polygon_mode != PolygonMode::Fill) {
    require(caps.core.fillModeNonSolid, context, "the fillModeNonSolid feature",
            std::string("polygon mode ") + to_string(state.polygon_mode));
  }
  const bool rasterizes_lines = is_line_topology(topology) || state.polygon_mode == PolygonMode::Line;
  if (state.line_width != 1.0f) {
    require(caps.core.wideLines, context, "the wideLines feature", fmt::format("line width {}", state.line_width));
    const float* range = caps.limits.lineWidthRange;
    require(!rasterizes_lines || (state.line_width >= range[0] && state.line_width <= range[1]), context,
            fmt::format("line widths outside [{}, {}]", range[0], range[1]),
            fmt::format("line width {}", state.line_width));
  }
  if (state.depth_bias.enable && state.depth_bias.clamp != 0.0f) {
    require(caps.core.depthBiasClamp, context, "the depthBiasClamp feature", "a non-zero depth bias clamp");
  }
  if (state.depth_clamp) require(caps.core.depthClamp, context, "the depthClamp feature", "depth clamp");
  if (state.depth_clip.has_value()) {
    require(caps.depth_clip_enable_ext, context, "VK_EXT_depth_clip_enable", "an explicit depth_clip");
    require(caps.depth_clip_enable, context, "the depthClipEnable feature", "an explicit depth_clip");
  }
  if (state.line_mode == LineMode::Default) return;
  const std::string why = std::string("line mode ") + to_string(state.line_mode);
  require(caps.line_rasterization_ext, context, "VK_EXT_line_rasterization", why);
  const bool feature = state.line_mode == LineMode::Rectangular ? caps.rectangular_lines
                       : state.line_mode == LineMode::Bresenham ? caps.bresenham_lines
                                                                : caps.smooth_lines;
  require(feature, context, "the matching VK_EXT_line_rasterization feature", why);
  // Observed with Mesa 22.3.6: drawing rectangular_smooth lines (line topologies or polygon mode
  // line) into the R32_UINT owner attachment crashes lavapipe (segfault in a rasterizer thread,
  // with or without validation). Smooth-line coverage is outside the CPU model anyway
  // (docs/lavapipe-rules.md §5.2), so refuse it instead of taking the process down.
  if (state.line_mode == LineMode::RectangularSmooth && rasterizes_lines && context.info().is_lavapipe) {
    throw NotSupportedError(
        fmt::format("{}: rectangular_smooth lines crash lavapipe when drawn into the "
                    "R32_UINT owner attachment",
                    context.info().name));
  }
}

PipelineCache::PipelineCache(const Context& context, size_t max_pipelines)
    : context_(context),
      max_pipelines_(std::max<size_t>(max_pipelines, 2)),
      vertex_(create_shader_module(context.device(), passthrough_vert, sizeof(passthrough_vert))),
      vertex_points_(create_shader_module(context.device(), passthrough_points_vert, sizeof(passthrough_points_vert))),
      fragment_(create_shader_module(context.device(), owner_frag, sizeof(owner_frag))),
      layout_(create_graphics_layout(context.device())) {}

VkRenderPass PipelineCache::render_pass(const AttachmentConfig& config) {
  auto found = render_passes_.find(config);
  if (found == render_passes_.end()) {
    found = render_passes_.emplace(config, create_render_pass(context_.device(), config)).first;
  }
  return found->second.get();
}

VkPipeline PipelineCache::graphics_pipeline(const AttachmentConfig& config, Topology topology,
                                            const RasterState& state) {
  const PipelineKey key = make_pipeline_key(config, topology, state);
  if (auto found = pipelines_.find(key); found != pipelines_.end()) {
    found->second.last_use = ++use_clock_;
    return found->second.pipeline.get();
  }
  require_state_support(context_, topology, state);

  const VkShaderModule vertex = draws_points(topology, state) ? vertex_points_.get() : vertex_.get();
  const VkPipelineShaderStageCreateInfo stages[] = {stage(VK_SHADER_STAGE_VERTEX_BIT, vertex),
                                                    stage(VK_SHADER_STAGE_FRAGMENT_BIT, fragment_.get())};
  const SharedStates shared;
  const VkPipelineInputAssemblyStateCreateInfo input_assembly = input_assembly_state(topology);
  RasterizationChain rasterization;
  fill_rasterization(state, rasterization);
  const VkPipelineMultisampleStateCreateInfo multisample = multisample_state(config.samples);
  const VkPipelineDepthStencilStateCreateInfo depth = depth_stencil_state(state.depth);

  VkGraphicsPipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &shared.vertex_input;
  info.pInputAssemblyState = &input_assembly;
  info.pViewportState = &shared.viewport;
  info.pRasterizationState = &rasterization.rasterization;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = config.depth_format == DepthFormat::None ? nullptr : &depth;
  info.pColorBlendState = &shared.blend;
  info.pDynamicState = &shared.dynamic;
  info.layout = layout_.get();
  info.renderPass = render_pass(config);
  info.subpass = 0;
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(api().vkCreateGraphicsPipelines(context_.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
        "vkCreateGraphicsPipelines");
  CachedPipeline entry{own(context_.device(), api().vkDestroyPipeline, pipeline), ++use_clock_};
  return pipelines_.emplace(key, std::move(entry)).first->second.pipeline.get();
}

size_t PipelineCache::trim() {
  if (pins_ > 0 || pipelines_.size() <= max_pipelines_) return 0;
  std::vector<uint64_t> uses;
  uses.reserve(pipelines_.size());
  for (const auto& [key, entry] : pipelines_) uses.push_back(entry.last_use);
  // Keep the most recent half: every stamp is distinct, so the cut is exact.
  const auto keep = static_cast<std::ptrdiff_t>(max_pipelines_ / 2);
  std::nth_element(uses.begin(), uses.end() - keep, uses.end());
  const uint64_t oldest_kept = *(uses.end() - keep);
  const size_t before = pipelines_.size();
  std::erase_if(pipelines_, [&](const auto& item) { return item.second.last_use < oldest_kept; });
  return before - pipelines_.size();
}

}  // namespace rastercmp::vk
