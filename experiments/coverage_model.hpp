// The theory of the fill maps (map_theory.hpp): Vulkan's coverage rule for triangles evaluated
// directly on a scene's design coordinates, with no renderer in the loop. A sample (pixel centre) is
// covered by a triangle where every edge function is positive, or zero on an edge the tie rule gives
// the triangle (Vulkan 28.7.1 "Basic Polygon Rasterization": the top-left rule, lavapipe-rules §2.2);
// a sample belongs to the first triangle of the draw that covers it (depth test Less, equal depths).
// The methods of the fill family differ only in the vertices the rule sees and in the tie rule:
//   exact path       vertices snapped to the 24.8 grid, halves to even (§2.1); top-left
//   snap=round_half_away  halves away from zero; top-left
//   tie_break=none   snapped; no edge owns its samples
//   scanline, even_odd, winding  the real (float) vertices; an edge's sample goes to the triangle
//                    on its left or top side (the notes' half-open spans)
//   float_edge       the real vertices; E >= 0 on every edge
// Every triangle is culled when its snapped area is 0 (the classic route keeps the exact set-up's
// degenerate test). Edge functions are evaluated in double: on the 24.8 grid inside a 16384-pixel
// frame every product is a multiple of 2^-16 below 2^30, so a snapped tie is exact; real vertices
// meet an edge exactly only where the design puts them there.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

namespace rastercmp::experiments {

using WindowTriangle = std::array<glm::dvec2, 3>;  // window pixels, y down

struct DesignTriangles {
  std::vector<WindowTriangle> triangles;  // in draw order
  uint32_t width = 64, height = 64;       // the frame the samples lie in
};

enum class ModelVertices { Real, SnapHalfEven, SnapHalfAway };
enum class ModelTies { TopLeft, None, All };

struct CoverageRule {
  ModelVertices vertices = ModelVertices::SnapHalfEven;
  ModelTies ties = ModelTies::TopLeft;
};

// The owner (index into triangles, or -1) of every sample of the frame, row by row.
std::vector<int32_t> model_owners(const DesignTriangles& design, CoverageRule rule);

// The samples whose owner differs between two rules: the predicted mismatch of a method against
// the exact path (coverage_mismatch; the fill maps' triangles are flat, so depth never differs alone).
uint64_t model_mismatch(const DesignTriangles& design, CoverageRule method, CoverageRule reference = {});

}  // namespace rastercmp::experiments
