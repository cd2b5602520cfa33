// Scene → JSON text (docs/scene-format.md) that loads back to the same Scene, bit for bit: the
// positions are written in clip space (space "clip", no camera: a camera or "pixels" scene was
// already converted on load) as the shortest decimal that reads back to the same float, and only
// the state that differs from the defaults is written. Non-finite coordinates and w = 0 are
// written with "allow_non_finite".
#pragma once

#include <string>

#include "model/scene.hpp"

namespace rastercmp::soak {

std::string scene_to_json_text(const Scene& scene);

// Writes the scene to `path` through a temporary file and a rename (never half-written).
void write_scene_file(const std::string& path, const Scene& scene);

}  // namespace rastercmp::soak
