// Per-tile depth bounds ("hi-z", docs/performance.md): the range of raw depth values stored in a
// tile, used to reject a triangle's whole rectangle when every sample would fail the depth test,
// or to skip the per-pixel compare when every sample would pass. Both decisions are exact, not
// heuristics:
//  - raw depth is a monotone function of px and of py (each step of z = fl(FMA?(dzdy, py,
//    FMA?(dzdx, px, a0)) + o), the clamps and the conversion is a rounded monotone operation), so
//    its minimum and maximum over a rectangle are at the rectangle's corners, as long as no step
//    overflows (checked: finite coefficients below 1e30);
//  - raw values compare as unsigned integers exactly as the depth test compares them: UNORM is an
//    unsigned compare (§3.6) and D32 values are floats in [+0, 1] (after the [0,1] clamp; the
//    frame is excluded when a clear value or depth clamp range could store anything else), whose
//    bit patterns order like the floats.
#pragma once

#include <cstdint>

#include "cpu_raster/exact/rasterize.hpp"
#include "cpu_raster/fast/fast_triangle.hpp"

namespace rastercmp::cpu::fast {

enum class BoundsState : uint8_t {
  Unknown,  // some write was not accounted for
  Loose,    // every stored value lies in [zmin, zmax]
  Exact,    // as Loose, and the bounds were measured or set by a full overwrite
};

struct TileBounds {
  uint32_t zmin = 0, zmax = 0;
  BoundsState state = BoundsState::Unknown;
};

// A tile of the frame: its depth bounds, whether its pixels hold the clear values yet ("fast
// clear": a tile is cleared by its worker when first drawn into, while it is in cache, or not at
// all when the first triangle overwrites every pixel; untouched tiles are cleared at the end), and
// the worker that draws it (render_fast.cpp; kUnownedRow in a row no worker owns).
struct TileState {
  TileBounds bounds;
  bool cleared = false;
  uint32_t worker = 0;
};

// Raw depth range of a triangle's samples over rectangle r; false when the plane is not finite
// enough for the corner argument.
struct FragmentRange {
  uint32_t lo = 0, hi = 0;
};
bool fragment_range(const FastTriangle& t, const PixelRect& r, const DepthTestState& depth, FragmentRange& out);

enum class DepthVerdict { AllFail, AllPass, PerPixel };

// The depth test of any fragment in `fragment` against any stored value in [zmin, zmax].
DepthVerdict classify_depth(CompareOp op, const FragmentRange& fragment, const TileBounds& tile);

// Measures the bounds of the stored values of tile rectangle r.
void measure_bounds(const uint32_t* depth, int32_t width, const PixelRect& r, bool avx2, TileBounds& tile);
void measure_bounds_avx2(const uint32_t* depth, int32_t width, const PixelRect& r, uint32_t& lo, uint32_t& hi);

// Whether raw values of this depth state order as the test orders them (see above): the depth
// clamp's lower bound must be a non-negative number.
bool depth_values_ordered(const DepthTestState& depth);

}  // namespace rastercmp::cpu::fast
