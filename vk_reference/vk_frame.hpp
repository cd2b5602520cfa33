// One scene made ready to run: attachments, uploaded geometry, read-back buffers and a command
// buffer recorded once (render pass, one draw call per Draw, read-back copies), plus its fence.
// A Frame holds pointers into the renderer's device and caches: it must not outlive them.
#pragma once

#include <optional>
#include <vector>

#include <vulkan/vulkan.h>

#include "model/render_result.hpp"
#include "model/scene.hpp"
#include "vk_reference/vk_attachments.hpp"
#include "vk_reference/vk_context.hpp"
#include "vk_reference/vk_gather.hpp"
#include "vk_reference/vk_pipeline.hpp"
#include "vk_reference/vk_reference.hpp"
#include "vk_reference/vk_resources.hpp"

namespace rastercmp::vk {

// Where one Draw's data sits in the shared vertex and index buffers, and what runs it.
struct DrawCall {
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDeviceSize vertex_offset = 0;  // bytes into Geometry::vertices
  VkDeviceSize index_offset = 0;   // bytes into Geometry::indices
  uint32_t vertex_count = 0;       // Draw::vertex_count()
  bool indexed = false;
  DepthBias depth_bias;  // the draw's factors (dynamic state); zero when bias is off
};

struct Geometry {
  Buffer vertices;                // every draw's positions_clip, vec4 float
  std::optional<Buffer> indices;  // every indexed draw's indices, uint32
  std::vector<DrawCall> calls;    // one per Scene::draws entry
};

// The gather pipelines a multisampled scene needs; the renderer makes them once.
struct Gathers {
  const SampleGather* owner = nullptr;  // every multisampled scene
  const SampleGather* depth = nullptr;  // multisampled scenes with depth
  // Multisampled scenes with UNORM depth: how the device samples that format
  // (measure_unorm_sampling); none: that depth is not read back.
  std::optional<UnormSampling> depth_sampling;
};

// Where the recorded copies put the results.
struct ReadBack {
  Buffer owner;  // width*height*samples uint32
  // Single-sample scenes with depth: the depth-aspect copy. Multisampled scenes whose depth the
  // device can sample: width*height*samples sampled floats' bits (depth_raw_from_sampled).
  std::optional<Buffer> depth;
  std::optional<SampleGather::Binding> gather;        // multisampled scenes: the owner
  std::optional<SampleGather::Binding> depth_gather;  // multisampled scenes with readable depth
};

class Frame final : public VulkanRenderer::Prepared {
 public:
  // `gathers.owner` is needed (non-null) only when scene.samples > 1, `gathers.depth` when the
  // multisampled scene also has depth.
  Frame(const Context& context, PipelineCache& pipelines, const Gathers& gathers, const Scene& scene);

  // Submits the recorded commands and waits; returns the seconds from vkQueueSubmit to the
  // fence signalling (the fence is reset before the clock starts).
  double submit_and_wait();

  RenderResult read_back() const;

 private:
  const Context& context_;
  PipelineCache::Pin pin_;  // the pipelines recorded below outlive this frame
  uint32_t width_, height_, samples_;
  DepthFormat depth_format_;
  std::optional<UnormSampling> depth_sampling_;  // Gathers::depth_sampling
  Attachments attachments_;
  Geometry geometry_;
  ReadBack read_back_;
  Owned<VkCommandBuffer> commands_;
  Owned<VkFence> fence_;
  bool submitted_ = false;
};

// Throws InputError (file = scene.source_path) for a scene no renderer can draw: a size outside
// 1..kMaxFramebufferSide, a depth clear outside [0, 1], more than kMaxDraws draws, or an index past
// the draw's positions. (The viewport is checked against the device's limits in Frame.)
void check_scene(const Scene& scene);

// Records the whole frame into `commands` (between begin and end).
void record_frame(VkCommandBuffer commands, const Scene& scene, VkRenderPass render_pass, VkPipelineLayout layout,
                  const Attachments& attachments, const Geometry& geometry, const ReadBack& read_back,
                  const Gathers& gathers);

}  // namespace rastercmp::vk
