// Shared pieces of the differential tests (test_differential*.cpp): one validated Vulkan renderer
// on lavapipe, a seeded random source, and the pixel-by-pixel comparison of the CPU lavapipe
// profile against the driver (owner id per sample, raw depth bits per sample).
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <glm/vec4.hpp>

#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/assemble.hpp"
#include "model/errors.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"
#include "tests/test_vulkan_support.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::differential {

// Deterministic on every platform: mt19937 bits turned into numbers by hand (the standard
// distributions are implementation-defined).
class Random {
 public:
  explicit Random(uint32_t seed) : engine_(seed) {}
  float uniform(float lo, float hi) { return lo + (hi - lo) * (float(engine_() >> 8) * (1.0f / 16777216.0f)); }
  int integer(int lo, int hi) { return lo + int(engine_() % uint32_t(hi - lo + 1)); }
  bool chance(float p) { return uniform(0.0f, 1.0f) < p; }
  template <class T>
  const T& pick(const std::vector<T>& values) {
    return values[size_t(integer(0, int(values.size()) - 1))];
  }

 private:
  std::mt19937 engine_;
};

using test::missing_vulkan_reason;
using test::shared_renderer;

struct DiffFigures {
  uint64_t scenes = 0, primitives = 0, covered_samples = 0, coverage_mismatches = 0, depth_mismatches = 0;
  void add(const DiffFigures& o) {
    scenes += o.scenes;
    primitives += o.primitives;
    covered_samples += o.covered_samples;
    coverage_mismatches += o.coverage_mismatches;
    depth_mismatches += o.depth_mismatches;
  }
};

inline uint64_t count_primitives(const Scene& scene) {
  uint64_t n = 0;
  for (const Draw& d : scene.draws) n += cpu::primitive_count(d);
  return n;
}

inline std::string describe_owner(uint32_t owner) {
  if (owner == kOwnerBackground) return "background";
  return fmt::format("draw {} prim {}", owner_draw(owner), owner_primitive(owner));
}

// Compares the two results sample by sample; `report` gets the first differing samples.
inline DiffFigures diff_results(const Scene& scene, const RenderResult& cpu, const RenderResult& vk,
                                std::string& report) {
  DiffFigures f;
  f.scenes = 1;
  f.primitives = count_primitives(scene);
  const bool depth = cpu.has_depth() && vk.has_depth();
  int listed = 0;
  for (uint32_t y = 0; y < vk.height; ++y) {
    for (uint32_t x = 0; x < vk.width; ++x) {
      for (uint32_t s = 0; s < vk.samples; ++s) {
        const size_t i = vk.index(x, y, s);
        if (vk.owner[i] != kOwnerBackground) ++f.covered_samples;
        const bool owner_differs = cpu.owner[i] != vk.owner[i];
        const bool depth_differs = depth && cpu.depth_raw[i] != vk.depth_raw[i];
        f.coverage_mismatches += owner_differs;
        f.depth_mismatches += depth_differs;
        if ((owner_differs || depth_differs) && listed++ < 8) {
          report += fmt::format("  ({}, {}) sample {}: cpu {} / vulkan {}", x, y, s, describe_owner(cpu.owner[i]),
                                describe_owner(vk.owner[i]));
          if (depth) report += fmt::format("; depth cpu {:#x} / vulkan {:#x}", cpu.depth_raw[i], vk.depth_raw[i]);
          report += "\n";
        }
      }
    }
  }
  return f;
}

// How the CPU side is configured; by default exactly as the driver behaves.
struct CpuVariant {
  std::vector<MethodChoice> methods;
  bool invert_fma = false;  // model the opposite of the driver's FMA behaviour
};

// Renders on both sides and returns the figures; asserts the layer stayed silent and both results
// have the same shape.
inline DiffFigures run_differential(const Scene& scene, const CpuVariant& variant, std::string& report) {
  VulkanRenderer& renderer = shared_renderer();
  const RenderResult vk = renderer.render(scene);
  for (const std::string& m : renderer.validation_messages()) ADD_FAILURE() << "validation: " << m;
  EXPECT_TRUE(renderer.validation_messages().empty());
  CpuOptions options;
  options.fma = renderer.device().fma != variant.invert_fma;
  options.lavapipe = &test::release_of(renderer);
  options.methods = variant.methods;
  const RenderResult cpu = render_cpu(scene, options);
  EXPECT_EQ(cpu.owner.size(), vk.owner.size());
  if (cpu.owner.size() != vk.owner.size()) return DiffFigures{};
  EXPECT_EQ(cpu.has_depth(), vk.has_depth());  // lavapipe samples multisampled depth too
  return diff_results(scene, cpu, vk, report);
}

// Framebuffer position → clip position for the default viewport (exact for power-of-two sizes).
inline glm::vec4 clip_from_window(float x, float y, float z, const Scene& scene, float w = 1.0f) {
  return {(2.0f * x / float(scene.width) - 1.0f) * w, (2.0f * y / float(scene.height) - 1.0f) * w, z * w, w};
}

inline Scene make_scene(const std::string& name, uint32_t width, uint32_t height, DepthFormat format) {
  Scene scene;
  scene.name = name;
  scene.width = width;
  scene.height = height;
  scene.depth_format = format;
  return scene;
}

inline DepthFormat format_for(uint32_t seed) {
  static const DepthFormat formats[] = {DepthFormat::D16Unorm, DepthFormat::X8D24Unorm, DepthFormat::D32Sfloat};
  return formats[seed % 3];
}

// Depth compare ALWAYS with writes: every primitive's depth reaches the attachment.
inline RasterState always_state() {
  RasterState state;
  state.depth.compare_op = CompareOp::Always;
  return state;
}

}  // namespace rastercmp::differential
