// Why a sample ended up as it did on the classic path (render_classic.hpp): the methods chosen per
// stage, then every primitive that reached the pixel after the clip and cull stages, in the order
// the visibility stage draws them (submission order for zbuffer, painting order for painter and
// bsp), each with the method's own decision there — the exact edge values, the fill's spans on the
// pixel's row (flood: outline or filled, and the seed), the line method's step — and the depth
// method's value, the raw stored depth, the replayed depth test and whether it became the owner.
// It runs the classic path's own stage functions, so "stored before/after" are what the render
// holds. Primitives the clip or cull stage removed are counted, not listed.
#pragma once

#include <cstdint>
#include <string>

#include "cpu_raster/exact/cpu_options.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Throws as render_classic does (UsageError, NotSupportedError) and UsageError for a pixel or
// sample outside the framebuffer.
std::string explain_classic_pixel(const Scene& scene, const CpuOptions& options, uint32_t x, uint32_t y,
                                  uint32_t sample = 0);

}  // namespace rastercmp
