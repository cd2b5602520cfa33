// The Vulkan reference: a minimal headless pipeline (lavapipe by default) that renders a Scene
// into an R32_UINT owner attachment and the scene's depth attachment and reads both back.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp {

struct VkOptions {
  std::string device;     // name substring or index; empty: lavapipe (llvmpipe)
  bool validate = false;  // enable VK_LAYER_KHRONOS_validation; messages are collected
  // Pipelines kept between frames; past it the least recently used half goes (vk_pipeline.hpp).
  size_t max_cached_pipelines = 256;
};

struct DeviceInfo {
  uint32_t index = 0;
  std::string name;
  std::string type;         // "cpu", "integrated-gpu", ...
  std::string driver_name;  // VkPhysicalDeviceDriverProperties::driverName
  std::string driver_info;  // e.g. "Mesa 22.3.6"
  std::string api_version;  // "1.3.230"
  uint32_t sub_pixel_precision_bits = 0;
  DeviceLimits limits;                     // what a capture records (sub_pixel_precision_bits repeated)
  std::vector<DepthFormat> depth_formats;  // renderable with optimal tiling
  std::vector<uint32_t> sample_counts;     // framebuffer colour & depth sample counts, e.g. {1, 4}
  bool is_lavapipe = false;
  bool fma = false;  // lavapipe only: whether it fuses on this host
};

// Lists the Vulkan devices. Throws EnvironmentError when no loader or ICD is present.
std::vector<DeviceInfo> list_vulkan_devices();

class VulkanRenderer {
 public:
  // Creates instance and device once for a whole run. Throws EnvironmentError.
  explicit VulkanRenderer(const VkOptions& options);
  ~VulkanRenderer();
  VulkanRenderer(const VulkanRenderer&) = delete;
  VulkanRenderer& operator=(const VulkanRenderer&) = delete;

  const DeviceInfo& device() const;

  // Renders and reads back. Throws NotSupportedError (state the device lacks),
  // DeviceError (device lost / out of memory), InputError (a scene Vulkan cannot take: an
  // index past the positions, a viewport outside the device's limits, more than kMaxDraws draws).
  // Single-sample scenes return owner and raw depth (copied out). Multisampled scenes return the
  // owner and raw depth of every sample, read by compute shaders (texelFetch of each sample; the
  // sampled depth float turned back into raw bits by the device's measured UNORM conversion,
  // vk_gather.hpp measure_unorm_sampling, vk_translate.hpp depth_raw_from_sampled). Where the
  // device cannot sample the multisampled depth format, or converts it some other way,
  // depth_raw stays empty.
  RenderResult render(const Scene& scene);

  // For benchmarks: resources and command buffer built once, then submitted many times.
  // A Prepared must not outlive its renderer; read_back needs at least one submit first.
  class Prepared {
   public:
    virtual ~Prepared() = default;
  };
  std::unique_ptr<Prepared> prepare(const Scene& scene);
  double submit_and_wait_seconds(Prepared& prepared);  // vkQueueSubmit → fence, nothing else
  RenderResult read_back(Prepared& prepared);

  // Validation-layer messages seen so far (warnings and errors), when validate is on.
  const std::vector<std::string>& validation_messages() const;

  // Graphics pipelines held in the cache now (bounded by VkOptions::max_cached_pipelines).
  size_t cached_pipelines() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rastercmp
