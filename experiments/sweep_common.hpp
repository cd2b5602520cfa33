// What every experiment command shares: its options, number formatting for the CSV (shortest
// round-trip, so the files are deterministic) and the CPU options of the exact path.
#pragma once

#include <string>
#include <vector>

#include "cpu_raster/cpu_raster.hpp"
#include "model/render_result.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::experiments {

struct SweepOptions {
  std::string out_dir;
  bool quick = false;   // a small grid, for the tests (< 30 s)
  bool resume = false;  // keep the CSV's points and compute only the missing ones
  // The timed charts (speed-accuracy, scene-needs): whether the process's allocator keeps the
  // memory a render frees (set by the command line, as `rastercmp bench` does: bench_stats.hpp
  // keep_freed_memory), recorded beside the timings. Where it is not kept, a method that builds
  // large lists pays page faults on every render (10-35 us each on a shared VM).
  bool freed_memory_kept = false;
};

// Shortest text that reads back as the same double.
std::string num(double value);
std::string flag(bool value);  // "true" / "false"

// The lavapipe release the installed driver is (the first lavapipe device's driverInfo), the oldest
// modelled one when there is none: what the sweeps compare with.
const LavapipeRelease& installed_lavapipe_release();

// The exact path as lavapipe on this host computes: its FMA, the installed release's rules (or
// the release set_reference_release pinned: a measurement that must not depend on the host).
CpuOptions exact_cpu_options();
void set_reference_release(const LavapipeRelease& release);

// Both backends on one scene.
struct BackendPair {
  RenderResult cpu, vk;
};
BackendPair render_both(VulkanRenderer& vk, const Scene& scene);

// "d16_unorm" etc. (model's to_string) and the bits of each format in sweep order.
std::vector<DepthFormat> sweep_depth_formats();

// Creates the folder; throws InputError when it cannot be written.
void prepare_out_dir(const std::string& dir);

// Writes JSON text atomically to DIR/NAME.
void write_json_file(const std::string& dir, const std::string& name, const std::string& json_text);

}  // namespace rastercmp::experiments
