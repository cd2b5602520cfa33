// Unit tests of the lean set-ups (lean_setup.hpp, clipped_pieces.hpp setup_piece) against the exact
// path's set-ups on random primitives: what they draw must be field for field the exact set-up's
// raster, what they drop must be what it does not rasterize, and what they hand back is left to it.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/line_setup.hpp"
#include "cpu_raster/exact/triangle_setup.hpp"
#include "cpu_raster/fast/clipped_pieces.hpp"
#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/lean_setup.hpp"
#include "tests/test_fast_support.hpp"

namespace rastercmp::cpu::fast {
namespace {

// A random draw state and set-up context for the set-up tests: every cull mode and facing, the
// depth test on or off, bias, every depth format, a 256x192 frame whose draw region cuts it (or,
// with chance `whole_frame`, is the frame).
void random_setup_case(fast_test::Random& r, double whole_frame, RasterState& state, SetupContext& ctx) {
  state.cull_mode = r.chance(0.5) ? CullMode::None : CullMode(r.below(4));
  state.front_face = r.chance(0.5) ? FrontFace::CounterClockwise : FrontFace::Clockwise;
  state.depth.test_enable = r.chance(0.8);
  state.depth_bias =
      DepthBias{r.chance(0.3), float(r.range(-4, 4)), float(r.range(-2, 2)), float(r.range(-0.01, 0.01))};
  ctx.framebuffer = PixelRect{0, 0, 255, 191};
  const int32_t x0 = int32_t(r.below(200)), y0 = int32_t(r.below(150));
  const int32_t x1 = x0 + int32_t(r.below(256 - uint32_t(x0))), y1 = y0 + int32_t(r.below(192 - uint32_t(y0)));
  ctx.region = r.chance(whole_frame) ? ctx.framebuffer : PixelRect{x0, y0, x1, y1};
  ctx.state = &state;
  ctx.depth_format = DepthFormat(r.below(4));
}

// A lean set-up's raster field by field against the full set-up's (want), both drawn.
void expect_same_raster(const RasterPrimitive& lean, const RasterPrimitive& want, int trial) {
  ASSERT_FALSE(want.binned) << "trial " << trial;
  ASSERT_FALSE(lean.binned) << "trial " << trial;
  ASSERT_EQ(lean.owner, want.owner) << "trial " << trial;
  ASSERT_EQ(lean.is_line, want.is_line) << "trial " << trial;
  ASSERT_EQ(lean.edge_count, want.edge_count) << "trial " << trial;
  ASSERT_EQ(lean.planes.count, want.planes.count) << "trial " << trial;
  for (uint32_t i = 0; i < want.planes.count; ++i) {
    ASSERT_EQ(lean.planes.plane[i].c, want.planes.plane[i].c) << "trial " << trial;
    ASSERT_EQ(lean.planes.plane[i].dcdx, want.planes.plane[i].dcdx) << "trial " << trial;
    ASSERT_EQ(lean.planes.plane[i].dcdy, want.planes.plane[i].dcdy) << "trial " << trial;
    ASSERT_EQ(lean.planes.plane[i].inclusive, want.planes.plane[i].inclusive) << "trial " << trial;
  }
  for (int k = 0; k < 4; ++k) {
    ASSERT_EQ(lean.vertex_fixed[k].x.raw, want.vertex_fixed[k].x.raw) << "trial " << trial;
    ASSERT_EQ(lean.vertex_fixed[k].y.raw, want.vertex_fixed[k].y.raw) << "trial " << trial;
  }
  ASSERT_EQ(lean.bbox, want.bbox) << "trial " << trial;
  ASSERT_EQ(lean.visit, want.visit) << "trial " << trial;
  ASSERT_EQ(lean.per_sample, want.per_sample) << "trial " << trial;
  ASSERT_EQ(lean.has_depth, want.has_depth) << "trial " << trial;
  ASSERT_EQ(std::bit_cast<uint32_t>(lean.depth.a0), std::bit_cast<uint32_t>(want.depth.a0)) << "trial " << trial;
  ASSERT_EQ(std::bit_cast<uint32_t>(lean.depth.dzdx), std::bit_cast<uint32_t>(want.depth.dzdx)) << "trial " << trial;
  ASSERT_EQ(std::bit_cast<uint32_t>(lean.depth.dzdy), std::bit_cast<uint32_t>(want.depth.dzdy)) << "trial " << trial;
  ASSERT_EQ(lean.offset.computed, want.offset.computed) << "trial " << trial;
  ASSERT_EQ(std::bit_cast<uint32_t>(lean.offset.offset), std::bit_cast<uint32_t>(want.offset.offset))
      << "trial " << trial;
}

// Counts a lean set-up's outcome and holds it to the full set-up's: Drawn must be its raster
// field by field, Dropped a fate other than Rasterized; Full is left to it.
struct LeanTally {
  int drawn = 0, dropped = 0, full = 0;
};
void expect_lean_outcome(LeanSetup outcome, const RasterPrimitive& lean, SetupFate fate, const RasterPrimitive& want,
                         int trial, LeanTally& tally) {
  switch (outcome) {
    case LeanSetup::Drawn:
      ++tally.drawn;
      ASSERT_EQ(fate, SetupFate::Rasterized) << "trial " << trial;
      expect_same_raster(lean, want, trial);
      break;
    case LeanSetup::Dropped:
      ++tally.dropped;
      ASSERT_NE(fate, SetupFate::Rasterized) << "trial " << trial;
      break;
    case LeanSetup::Full: ++tally.full; break;
  }
}

// setup_piece (the lean set-up of clipped pieces) gives setup_triangle then fast_triangle_of for
// every piece it draws, drops exactly what setup_triangle does not rasterize, and hands back
// (Full) only what takes llvmpipe's wrapping set-up or fails to snap: random window triangles of
// every size and facing, corners past the direct range and the 24.8 bound, NaN corners, every
// cull mode, depth format and bias, regions that cut them or miss them.
TEST(FastClippedPieces, LeanSetUpGivesTheExactPathsTriangle) {
  fast_test::Random r(29);
  int drawn = 0, dropped = 0, full = 0;
  for (int trial = 0; trial < 40000; ++trial) {
    RasterState state;
    SetupContext ctx;
    random_setup_case(r, 0.0, state, ctx);
    std::array<WindowVertex, 3> window;
    // past the direct range (2^23 fixed units), large, small
    const double spread = r.chance(0.1) ? 3e7 : r.chance(0.3) ? 400.0 : 12.0;
    const bool near_region = r.chance(0.7);  // most around the region, some anywhere
    const double cx = near_region ? r.range(ctx.region.x0 - 4, ctx.region.x1 + 4) : r.range(-40, 300);
    const double cy = near_region ? r.range(ctx.region.y0 - 4, ctx.region.y1 + 4) : r.range(-40, 230);
    for (WindowVertex& v : window) {
      const float x = float(cx + r.range(-spread, spread)), y = float(cy + r.range(-spread, spread));
      v = WindowVertex{x, y, float(r.range(-0.2, 1.2))};
    }
    if (r.chance(0.01)) window[r.below(3)].y = std::nanf("");
    if (r.chance(0.02)) window[1] = window[0];  // degenerate
    const uint32_t owner = 1 + r.below(1000);
    const TriangleSetup setup = setup_triangle(window, owner, ctx);
    FastTriangle lean;
    switch (setup_piece(window, owner, ctx, ctx.region, lean)) {
      case PieceSetup::Drawn: {
        ++drawn;
        ASSERT_EQ(setup.fate, SetupFate::Rasterized) << "trial " << trial;
        ASSERT_FALSE(setup.raster.binned) << "trial " << trial;
        const FastTriangle want = fast_triangle_of(setup.raster, ctx.region);
        for (int k = 0; k < 3; ++k) {
          ASSERT_EQ(lean.x_fixed[k], want.x_fixed[k]) << "trial " << trial;
          ASSERT_EQ(lean.y_fixed[k], want.y_fixed[k]) << "trial " << trial;
        }
        ASSERT_EQ(lean.rect, want.rect) << "trial " << trial;
        ASSERT_EQ(std::bit_cast<uint32_t>(lean.a0), std::bit_cast<uint32_t>(want.a0)) << "trial " << trial;
        ASSERT_EQ(std::bit_cast<uint32_t>(lean.dzdx), std::bit_cast<uint32_t>(want.dzdx)) << "trial " << trial;
        ASSERT_EQ(std::bit_cast<uint32_t>(lean.dzdy), std::bit_cast<uint32_t>(want.dzdy)) << "trial " << trial;
        ASSERT_EQ(std::bit_cast<uint32_t>(lean.offset), std::bit_cast<uint32_t>(want.offset)) << "trial " << trial;
        ASSERT_EQ(lean.owner, want.owner) << "trial " << trial;
        break;
      }
      case PieceSetup::Dropped:
        ++dropped;
        ASSERT_NE(setup.fate, SetupFate::Rasterized) << "trial " << trial;
        break;
      case PieceSetup::Full:
        ++full;
        ASSERT_TRUE(setup.fate != SetupFate::Rasterized || setup.raster.binned) << "trial " << trial;
        break;
    }
  }
  EXPECT_GT(drawn, 12000);  // 16943, 18703 and 4354 of the 40000
  EXPECT_GT(dropped, 12000);
  EXPECT_GT(full, 2500);
}

// setup_triangle_lean (lean_setup.hpp) against setup_triangle on random triangles in 1x and 4x
// frames: snapped to nearest even or half away (not lean), past the direct range, NaN, degenerate,
// culled, around and across scissored regions (the scissor planes, the multisample quirk, the
// sample-exact scissor of later releases), with and without depth and bias. Drawn must give
// setup_triangle's raster field by field, Dropped a fate other than Rasterized, Full whatever it is.
TEST(FastLeanSetup, LeanSetupEqualsSetupTriangle) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "the host runs no AVX2";
  fast_test::Random r(41);
  LeanTally tally;
  RasterPrimitive lean;  // reused, as BandWorker reuses it
  const DenormalsFlushed ftz_daz;
  for (int trial = 0; trial < 40000; ++trial) {
    RasterState state;
    SetupContext ctx;
    random_setup_case(r, 0.3, state, ctx);
    ctx.multisample = r.chance(0.5);
    if (r.chance(0.05)) ctx.methods.snap = SnapRounding::HalfAwayFromZero;
    if (r.chance(0.1)) ctx.skips.depth_only_when_attached = false;
    std::array<WindowVertex, 3> window;
    const double spread = r.chance(0.1) ? 3e7 : r.chance(0.3) ? 400.0 : r.chance(0.5) ? 12.0 : 2.0;
    // the scissor planes of 26.2 (sample-exact); its set-up refuses the wrapping one
    if (spread < 1e6 && r.chance(0.2)) ctx.rules = LavapipeRules::of(MesaVersion{26, 2, 6});
    const bool near_region = r.chance(0.7);
    const double cx = near_region ? r.range(ctx.region.x0 - 4, ctx.region.x1 + 4) : r.range(-40, 300);
    const double cy = near_region ? r.range(ctx.region.y0 - 4, ctx.region.y1 + 4) : r.range(-40, 230);
    for (WindowVertex& v : window) {
      // a quarter on the 1/256 grid and its half steps (ties of the rounding)
      const double x = cx + r.range(-spread, spread), y = cy + r.range(-spread, spread);
      v = r.chance(0.25) ? WindowVertex{float(std::round(x * 512) / 512), float(std::round(y * 512) / 512), 0.5f}
                         : WindowVertex{float(x), float(y), float(r.range(-0.2, 1.2))};
    }
    if (r.chance(0.01)) window[r.below(3)].y = std::nanf("");
    if (r.chance(0.02)) window[1] = window[0];  // degenerate
    const uint32_t owner = 1 + r.below(1000);
    const TriangleSetup setup = setup_triangle(window, owner, ctx);
    expect_lean_outcome(setup_triangle_lean(window, owner, ctx, lean), lean, setup.fate, setup.raster, trial, tally);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(tally.drawn, 12000);
  EXPECT_GT(tally.dropped, 8000);
  EXPECT_GT(tally.full, 2000);
}

// setup_line_lean against setup_line on random lines in 1x and 4x frames of the three releases
// (22.3.6's util_iround, lrintf from 23.1, the depth plane at the centre of 25.3, the sample-exact
// scissor of 26.2): every line mode (Bresenham ones must be handed back), widths from 0.5 to 9 px,
// ends on the 1/256 grid and its half steps (the roundings' ties), lines past the direct range and
// the 24.8 bound, NaN and degenerate ones, tiny lengths and depths (denormal results), regions that
// cut them or miss them, the depth skip off. Drawn must be setup_line's raster field by field,
// Dropped a fate other than Rasterized; and where the lean set-up decides (Drawn, Dropped), its
// operations raise the MXCSR's denormal flags exactly when setup_line's do (the walk's trailing
// run relies on it: BandWorker::setup_line_lean_flushed).
TEST(FastLeanSetup, LeanLineSetupEqualsSetupLine) {
  if (!host_has_avx2_fma()) GTEST_SKIP() << "the host runs no AVX2";
  fast_test::Random r(43);
  LeanTally tally;
  int flagged = 0;
  RasterPrimitive lean;  // reused, as BandWorker reuses it
  const DenormalsFlushed ftz_daz;
  const std::array<MesaVersion, 4> releases{MesaVersion{22, 3, 6}, MesaVersion{25, 0, 7}, MesaVersion{25, 3, 0},
                                            MesaVersion{26, 2, 6}};
  for (int trial = 0; trial < 40000; ++trial) {
    RasterState state;
    SetupContext ctx;
    random_setup_case(r, 0.3, state, ctx);
    ctx.multisample = r.chance(0.3);
    const double spread = r.chance(0.05) ? 3e7 : r.chance(0.3) ? 400.0 : r.chance(0.5) ? 40.0 : 3.0;
    // 26.2's set-up refuses the wrapping one (NotSupportedError)
    ctx.rules = LavapipeRules::of(releases[r.below(uint32_t(releases.size()) - (spread < 1e6 ? 0 : 1))]);
    if (r.chance(0.1)) ctx.skips.depth_only_when_attached = false;
    state.line_mode = r.chance(0.1) ? LineMode(r.below(4)) : LineMode::Default;
    state.line_width = r.chance(0.6) ? 1.0f : float(r.range(0.5, 9.0));
    const bool near_region = r.chance(0.7);
    const double cx = near_region ? r.range(ctx.region.x0 - 4, ctx.region.x1 + 4) : r.range(-40, 300);
    const double cy = near_region ? r.range(ctx.region.y0 - 4, ctx.region.y1 + 4) : r.range(-40, 230);
    std::array<WindowVertex, 2> window;
    for (WindowVertex& v : window) {
      const double x = cx + r.range(-spread, spread), y = cy + r.range(-spread, spread);
      v = r.chance(0.25) ? WindowVertex{float(std::round(x * 512) / 512), float(std::round(y * 512) / 512), 0.5f}
                         : WindowVertex{float(x), float(y), float(r.range(-0.2, 1.2))};
    }
    if (r.chance(0.05)) {  // depths near 0: depth steps below FLT_MIN
      window[0].z = float(r.range(-1, 1)) * 1e-36f;
      window[1].z = 0.0f;
    }
    if (r.chance(0.02)) {  // ends near the origin: a squared length below FLT_MIN
      window[0].x = float(r.range(-1, 1)) * 1e-19f;
      window[0].y = float(r.range(-1, 1)) * 1e-19f;
      window[1] = WindowVertex{0.0f, 0.0f, 0.5f};
    }
    if (r.chance(0.01)) window[r.below(2)].x = std::nanf("");
    if (r.chance(0.02)) window[1] = window[0];  // degenerate
    const uint32_t owner = 1 + r.below(1000);
    clear_denormal_flags();
    const LineSetup setup = setup_line(window, owner, ctx);
    const bool setup_flags = denormal_flags_raised();
    clear_denormal_flags();
    const LeanSetup outcome = setup_line_lean(window, owner, ctx, lean);
    const bool lean_flags = denormal_flags_raised();
    if (outcome != LeanSetup::Full) {
      ASSERT_EQ(lean_flags, setup_flags) << "trial " << trial;
      flagged += lean_flags ? 1 : 0;
    }
    expect_lean_outcome(outcome, lean, setup.fate, setup.raster, trial, tally);
    if (HasFatalFailure()) break;
  }
  clear_denormal_flags();
  EXPECT_GT(tally.drawn, 15000);  // 19725, 17059, 3216 and 1103 of the 40000
  EXPECT_GT(tally.dropped, 12000);
  EXPECT_GT(tally.full, 2000);
  EXPECT_GT(flagged, 500);
}

}  // namespace
}  // namespace rastercmp::cpu::fast
