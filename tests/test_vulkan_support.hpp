// What the tests that render on the real driver share: why no Vulkan device is there (empty when
// one is), and one renderer (instance + device + pipeline cache, validation layer on) for the whole
// test binary, as the CLI uses it.
//
// The renderer is destroyed when the test program ends, by a global test environment, while the
// validation layer is still loaded: a function-local static would be destroyed at exit, after the
// loader may have unloaded the layer (validation layers 1.4 crash there).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "model/errors.hpp"
#include "model/lavapipe_release.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::test {

inline std::string missing_vulkan_reason() {
  try {
    return list_vulkan_devices().empty() ? "no Vulkan device" : "";
  } catch (const EnvironmentError& e) {
    return e.what();
  }
}

class SharedRendererEnvironment : public ::testing::Environment {
 public:
  VulkanRenderer& renderer() {
    if (!renderer_) renderer_ = std::make_unique<VulkanRenderer>(VkOptions{.device = "", .validate = true});
    return *renderer_;
  }
  void TearDown() override { renderer_.reset(); }

 private:
  std::unique_ptr<VulkanRenderer> renderer_;
};

// Registered once per test program, before main (gtest owns and deletes it).
inline SharedRendererEnvironment* const kSharedRendererEnvironment =
    static_cast<SharedRendererEnvironment*>(::testing::AddGlobalTestEnvironment(new SharedRendererEnvironment));

inline VulkanRenderer& shared_renderer() { return kSharedRendererEnvironment->renderer(); }

// The lavapipe release the CPU models to match `renderer`'s driver (--profile lavapipe does the same).
inline const LavapipeRelease& release_of(const VulkanRenderer& renderer) {
  return *lavapipe_release_for_driver(renderer.device().driver_info).release;
}

}  // namespace rastercmp::test
