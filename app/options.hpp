// Options shared by the commands that render (render, compare, explain, conformance).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cpu_raster/cpu_raster.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::app {

struct RenderOptions {
  std::string profile = "lavapipe";  // cpu profile: lavapipe | spec
  std::string fma = "auto";          // cpu arithmetic: auto (what lavapipe does here) | on | off
  std::vector<std::string> methods;  // STAGE=NAME
  unsigned threads = 0;              // cpu: 0 exact scalar path, >= 1 fast path threads
  std::string device;                // vulkan device name substring or index
  bool validate = false;             // vulkan validation layer
};

// Adds --profile, --fma, --method, --threads, --device, --validate to a subcommand.
void add_render_options(CLI::App& cmd, RenderOptions& options);

// Translates the options; throws UsageError for a bad --method or --profile value.
CpuOptions make_cpu_options(const RenderOptions& options, const Scene* scene = nullptr);
VkOptions make_vk_options(const RenderOptions& options);

}  // namespace rastercmp::app
