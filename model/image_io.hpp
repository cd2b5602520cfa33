// Writing and reading what a renderer produced (OpenImageIO). Every file is written to a
// temporary name in the same folder and renamed, so a reader never sees half a file.
//
// Files in an output folder:
//   owner.tif        lossless owner ids: uint32, one channel per sample
//   owner.png        false colour for people (background black, each owner a stable hue)
//   depth.exr        depth value as float (single-sample scenes with depth)
//   depth_raw.tif    raw stored bits: uint32 (D16 in the low 16 bits, X8_D24 in the low 24)
//   render.json      backend, device, fma, size, samples, depth format; for a Vulkan render also
//                    device_name, driver and the device's limits (DeviceLimits, Vulkan names)
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "model/render_result.hpp"

namespace rastercmp {

// Creates `dir` if needed and checks it is writable. Throws InputError (file = dir) if not.
void ensure_output_dir(const std::string& dir);

void write_render_outputs(const RenderResult&, const std::string& dir);

// Reads owner.tif / depth_raw.tif / render.json back (tests, merge, judged captures). Throws
// InputError naming the file that is missing, unreadable or disagrees with render.json.
RenderResult read_render_outputs(const std::string& dir);

// render.json alone: everything read_render_outputs returns but the images.
RenderResult read_render_info(const std::string& dir);

// Atomic text write: temp file + rename.
void write_text_file_atomic(const std::string& path, const std::string& text);

// Files that must agree (a run's results.csv and summary.json): every one is written to its
// temporary name first, and only when all are written are they renamed, in the order given. A
// write that fails (a full disk) removes the temporaries and leaves the earlier set as it was;
// renames need no space, so only a kill between two renames can leave them apart.
void write_text_files_together(const std::vector<std::pair<std::string, std::string>>& files);

// Stable false colour of an owner id (background: black).
void owner_false_colour(uint32_t owner, unsigned char rgb[3]);

}  // namespace rastercmp
