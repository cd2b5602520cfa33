// The float facing cull of lavapipe's draw pipeline, draw_pipe_cull.c cull_tri (docs/lavapipe-rules.md
// §2.6, step 8). It runs after the clipper, only for draws whose vertices needed clipping (the
// "pipelined" chunk flag, §1.5) and only when the cull mode is not NONE. llvmpipe's fixed-point
// cull runs afterwards regardless; the two can disagree on slivers.
#pragma once

#include <array>

#include "cpu_raster/exact/viewport.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu {

// det = (v0-v2).x*(v1-v2).y - (v0-v2).y*(v1-v2).x in float; det < 0 is counter-clockwise.
float pipeline_cull_determinant(const std::array<WindowVertex, 3>& window);

// True when the float cull drops the triangle: its face is culled, or det == 0 with BACK culled.
bool pipeline_cull_drops(float det, CullMode cull, FrontFace front_face);

}  // namespace rastercmp::cpu
