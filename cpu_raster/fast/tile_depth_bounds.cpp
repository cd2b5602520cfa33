#include "cpu_raster/fast/tile_depth_bounds.hpp"

#include <algorithm>
#include <cmath>

#include "cpu_raster/exact/depth_sample.hpp"

namespace rastercmp::cpu::fast {
namespace {

bool finite_below(float value, float limit) { return std::fabs(value) < limit; }  // false for NaN and Inf

}  // namespace

bool fragment_range(const FastTriangle& t, const PixelRect& r, const DepthTestState& depth, FragmentRange& out) {
  constexpr float kLimit = 1e30f;  // |coefficient| * 2^15 + |a0| stays far below FLT_MAX: no Inf, no NaN
  if (!finite_below(t.a0, kLimit) || !finite_below(t.dzdx, kLimit) || !finite_below(t.dzdy, kLimit) ||
      !finite_below(t.offset, kLimit))
    return false;
  const DepthPlane plane{t.a0, t.dzdx, t.dzdy};
  const int32_t xs[2] = {r.x0, r.x1}, ys[2] = {r.y0, r.y1};
  out.lo = UINT32_MAX;
  out.hi = 0;
  for (int32_t y : ys) {
    for (int32_t x : xs) {
      const uint32_t raw = sample_depth(plane, t.offset, float(x), float(y), depth.range, depth.format, depth.fma).raw;
      out.lo = std::min(out.lo, raw);
      out.hi = std::max(out.hi, raw);
    }
  }
  return true;
}

DepthVerdict classify_depth(CompareOp op, const FragmentRange& f, const TileBounds& tile) {
  const bool below = f.hi<tile.zmin, above = f.lo> tile.zmax;  // every fragment vs every stored value
  switch (op) {
    case CompareOp::Never: return DepthVerdict::AllFail;
    case CompareOp::Always: return DepthVerdict::AllPass;
    case CompareOp::Less:
      return f.lo >= tile.zmax ? DepthVerdict::AllFail : below ? DepthVerdict::AllPass : DepthVerdict::PerPixel;
    case CompareOp::LessOrEqual:
      return above ? DepthVerdict::AllFail : f.hi <= tile.zmin ? DepthVerdict::AllPass : DepthVerdict::PerPixel;
    case CompareOp::Greater:
      return f.hi <= tile.zmin ? DepthVerdict::AllFail : above ? DepthVerdict::AllPass : DepthVerdict::PerPixel;
    case CompareOp::GreaterOrEqual:
      return below ? DepthVerdict::AllFail : f.lo >= tile.zmax ? DepthVerdict::AllPass : DepthVerdict::PerPixel;
    case CompareOp::Equal: return below || above ? DepthVerdict::AllFail : DepthVerdict::PerPixel;
    case CompareOp::NotEqual: return below || above ? DepthVerdict::AllPass : DepthVerdict::PerPixel;
  }
  return DepthVerdict::PerPixel;
}

void measure_bounds(const uint32_t* depth, int32_t width, const PixelRect& r, bool avx2, TileBounds& tile) {
  uint32_t lo = UINT32_MAX, hi = 0;
  if (avx2) {
    measure_bounds_avx2(depth, width, r, lo, hi);
  } else {
    for (int32_t y = r.y0; y <= r.y1; ++y) {
      const uint32_t* row = depth + size_t(y) * size_t(width);
      for (int32_t x = r.x0; x <= r.x1; ++x) {
        lo = std::min(lo, row[x]);
        hi = std::max(hi, row[x]);
      }
    }
  }
  tile = TileBounds{lo, hi, BoundsState::Exact};
}

bool depth_values_ordered(const DepthTestState& depth) {
  return !depth.range.clamp || (depth.range.zmin >= 0.0f && !std::signbit(depth.range.zmin));
}

}  // namespace rastercmp::cpu::fast
