// Random scenes built from the scene format's corner cases (docs/soak.md). Each family stresses one
// part of the specification; every scene goes through the JSON writer and the loader before it is
// used, so what runs is exactly what a written file reproduces.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/scene.hpp"

namespace rastercmp::soak {

// The families, in the order the soak cycles through them.
const std::vector<std::string>& family_names();
bool is_family(const std::string& name);

// Scene `index` of family `family` for `seed`: a pure function of its arguments. The scene is
// named soak.<family>.s<seed>.n<index>. Throws std::logic_error if the generator produced a scene
// the loader rejects (a generator bug).
Scene generate_scene(const std::string& family, uint64_t seed, uint64_t index);

}  // namespace rastercmp::soak
