// Primitive assembly facts the soak and the reducer need, from the Vulkan specification
// ("Primitive Topologies"): how many primitives a draw has and which vertices make each.
#pragma once

#include <cstdint>
#include <vector>

#include "model/scene.hpp"

namespace rastercmp::soak {

// Vertices per primitive of a list topology: 1, 2 or 3.
uint32_t vertices_per_primitive(Topology topology);

// Primitives of a draw (its vertex count after indices and count).
uint64_t primitive_count(const Draw& draw);
uint64_t primitive_count(const Scene& scene);

// The position indices of primitive `p` of a draw, in the specification's order:
// strip triangle i = (i, i + 1 + i % 2, i + 2 - i % 2), fan triangle i = (i + 1, i + 2, 0),
// line strip segment i = (i, i + 1).
std::vector<uint32_t> primitive_vertices(const Draw& draw, uint64_t p);

}  // namespace rastercmp::soak
