// The geometry half of the classic path, per draw: assemble → clip (exact or classic) → cull
// (exact: lavapipe's float pipeline cull and fixed-point set-up cull; normal_dot_view: N·V in
// clip space before clipping) → the exact set-up. The exact set-up still decides which
// primitives survive (zero area, bounding box outside the draw region) and provides the edge
// planes, the depth plane and the depth bias; the fill, line, depth and visibility stages decide
// what to do with them (classic_fragments.hpp, render_classic.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cpu_raster/classic/classic_clip.hpp"
#include "cpu_raster/classic/classic_cull.hpp"
#include "cpu_raster/classic/classic_methods.hpp"
#include "cpu_raster/exact/front_end.hpp"
#include "cpu_raster/exact/rasterize.hpp"

namespace rastercmp::cpu::classic {

struct ClassicPrimitive {
  uint32_t draw_index = 0;
  uint32_t primitive_index = 0;
  bool is_line = false;
  bool clipped = false;                  // the clip stage made a vertex of this primitive
  uint32_t piece = 0;                    // which of the clipped fan's triangles
  uint32_t pieces = 1;                   // how many the clip stage made of the primitive
  std::array<WindowVertex, 3> window{};  // after clipping, emit order (2 used for lines)
  std::array<float, 3> w_clip{1, 1, 1};  // clip w of those vertices
  RasterPrimitive raster;                // the exact set-up's result (rasterized)
  DepthTestState depth;
  // What the clip method decided on (explain): lines clipped by a classic line clipper carry its
  // trace; triangles under sutherland_hodgman or weiler_atherton the 6-bit clip-space outcodes of
  // their three vertices before clipping (clip_volume.hpp).
  bool line_clip_traced = false;
  LineClipTrace line_clip;
  bool vertex_codes_traced = false;
  std::array<uint8_t, 3> vertex_codes{};
};

// A triangle cull=normal_dot_view removed before clipping, with the test's variables (explain).
struct CulledTriangle {
  uint32_t draw_index = 0;
  uint32_t primitive_index = 0;
  std::array<glm::vec4, 3> pos_clip{};
  std::array<WindowVertex, 3> window{};  // the JIT viewport transform of the unclipped vertices
  NormalDotView test;
};

// Appends the primitives of draw `draw_index` that reach rasterization, in primitive order, and,
// when `culled` is given, the triangles normal_dot_view removed.
void collect_primitives(const FrameContext& frame, uint32_t draw_index, const ClassicMethods& methods,
                        std::vector<ClassicPrimitive>& out, std::vector<CulledTriangle>* culled = nullptr);

}  // namespace rastercmp::cpu::classic
