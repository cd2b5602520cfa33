// The method chosen for each stage of the classic path (docs/methods.md "Selecting a method").
// `exact` (or zbuffer) everywhere is the exact lavapipe path; any other name routes the stage
// through the matching module of cpu_raster/methods/. The exact path's own ablations (snap,
// tie_break) are passed through to its set-up (cpu_raster/setup_methods.hpp).
#pragma once

#include <vector>

#include "cpu_raster/exact/setup_methods.hpp"
#include "model/scene.hpp"

namespace rastercmp::cpu::classic {

enum class ClipMethod {
  Exact,
  SutherlandHodgman,
  WeilerAtherton,
  CohenSutherland,
  CohenSutherland3d,
  LiangBarsky,
  CyrusBeck
};
enum class FillMethod { Exact, Scanline, FloatEdge, EvenOdd, Winding, Flood };
enum class LineMethod { Exact, Dda, Bresenham };
enum class DepthMethod { Exact, NoFma, Bilinear, PerspectiveCorrect, PseudoDepth };
enum class VisibilityMethod { ZBuffer, Painter, Bsp };
enum class CullMethod { Exact, NormalDotView };

struct ClassicMethods {
  ClipMethod clip = ClipMethod::Exact;
  FillMethod fill = FillMethod::Exact;
  LineMethod line = LineMethod::Exact;
  DepthMethod depth = DepthMethod::Exact;
  VisibilityMethod visibility = VisibilityMethod::ZBuffer;
  CullMethod cull = CullMethod::Exact;
  double pseudo_far = 0;  // DepthMethod::PseudoDepth: the far plane (near is 25)
  SetupMethods setup;     // snap, tie_break

  // Coverage or depth decided outside the exact rasterizer: one sample per pixel only.
  bool per_pixel() const {
    return fill != FillMethod::Exact || line != LineMethod::Exact || depth == DepthMethod::Bilinear ||
           depth == DepthMethod::PerspectiveCorrect || depth == DepthMethod::PseudoDepth ||
           visibility != VisibilityMethod::ZBuffer;
  }
};

// The stages and names of method_registry.hpp. Throws UsageError naming the valid stages or the
// valid names of the stage.
ClassicMethods parse_classic_methods(const std::vector<MethodChoice>& choices);

// True when a choice names one of the classic stages (anything but snap and tie_break).
bool names_classic_stage(const std::vector<MethodChoice>& choices);

}  // namespace rastercmp::cpu::classic
