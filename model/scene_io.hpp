// Scene files (JSON) → Scene. Every field is checked: unknown keys, wrong types and
// out-of-range values raise InputError naming the file, the JSON path and what was expected.
#pragma once

#include <string>
#include <string_view>

#include "model/scene.hpp"

namespace rastercmp {

// Reads and validates a scene file. Throws InputError.
Scene load_scene_file(const std::string& path);

// Parses scene text; `file` is only used in messages. Throws InputError.
Scene parse_scene(std::string_view text, const std::string& file);

}  // namespace rastercmp
