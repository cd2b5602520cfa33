// Scene files (JSON) → Scene. Every field is checked: unknown keys, wrong types and
// out-of-range values raise InputError naming the file, the JSON path and what was expected.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "model/scene.hpp"

namespace rastercmp {

// The largest scene file read (docs/scene-format.md); a larger one, or a file that never ends
// (/dev/zero), is refused before parsing.
inline constexpr size_t kMaxSceneFileBytes = size_t(64) << 20;

// Reads and validates a scene file. Throws InputError.
Scene load_scene_file(const std::string& path);

// Parses scene text; `file` is only used in messages. Throws InputError.
Scene parse_scene(std::string_view text, const std::string& file);

}  // namespace rastercmp
