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

// --profile lavapipe: the modelled release `driver_info` (a lavapipe device's) is, printing to
// stderr why it is another when that release is not modelled. Nothing for a forced release.
void pick_lavapipe_release(CpuOptions& cpu, const std::string& driver_info);
// The same for a command without a device of its own (render --backend cpu): the installed
// lavapipe's release, or the newest modelled one, with a warning, when none can be found.
void pick_installed_lavapipe_release(CpuOptions& cpu);

// Throws InputError (the file, $.methods.STAGE, the accepted names) for a scene "methods" entry
// the CPU renderer does not know.
void check_scene_methods(const Scene& scene, const std::string& path);

// An output folder made (with ensure_output_dir) before any work, so that an unwritable one is
// exit 2 at once; if the command then fails, the destructor removes the folders it created, as
// long as they are still empty. keep() once the outputs are written.
class OutputFolder {
 public:
  explicit OutputFolder(const std::string& dir);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  void keep() { created_.clear(); }

 private:
  void remove_empty_created();
  std::vector<std::string> created_;  // deepest first
};

// For --json FILE and the like, before any work: throws InputError when FILE exists and is not a
// regular file (a folder, say); returns the folder it goes in ("." when none is named).
std::string output_file_folder(const std::string& file);

// load_scene_file and check_scene_methods: a scene file as the commands that render read it.
Scene load_checked_scene(const std::string& path);

}  // namespace rastercmp::app
