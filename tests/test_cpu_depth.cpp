// Depth: the plane, the polygon offset, clamping, conversion to the stored bits and the compare
// (docs/lavapipe-rules.md §3, §4; steps 14-17), with answers worked out by hand.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "cpu_raster/exact/depth_plane.hpp"
#include "cpu_raster/exact/depth_sample.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/viewport.hpp"

namespace rastercmp::cpu {
namespace {

// D16 stores the low 16 mantissa bits of fl(fl(z * (1 - 2^-16)) + 128): round half to even of
// z*65535 computed in two float steps. 0.5 -> 32767.5 -> tie, even 32768; 0.75 -> 49151.25 ->
// 49151; 0.25 -> 16383.75 -> 16384.
TEST(CpuDepth, D16ConversionRoundsAtTheMagicNumberBoundary) {
  EXPECT_EQ(depth_to_raw(DepthFormat::D16Unorm, 0.0f), 0u);
  EXPECT_EQ(depth_to_raw(DepthFormat::D16Unorm, 1.0f), 0xFFFFu);
  EXPECT_EQ(depth_to_raw(DepthFormat::D16Unorm, 0.5f), 0x8000u);
  EXPECT_EQ(depth_to_raw(DepthFormat::D16Unorm, 0.75f), 0xBFFFu);
  EXPECT_EQ(depth_to_raw(DepthFormat::D16Unorm, 0.25f), 0x4000u);
  EXPECT_EQ(depth_to_raw(DepthFormat::D16Unorm, 1.0f / 65535), 1u);
}

// D24: cvtps2dq(fl(z * 16777215)). 0.5 -> 8388607.5 exactly -> even 8388608; one float below 0.5
// -> 8388607.0000000298 rounds to the float 8388607; one above -> 8388608.4999999 -> float 8388608.
TEST(CpuDepth, D24ConversionRoundsToNearestEvenAfterAFloatMultiply) {
  EXPECT_EQ(depth_to_raw(DepthFormat::X8D24Unorm, 0.0f), 0u);
  EXPECT_EQ(depth_to_raw(DepthFormat::X8D24Unorm, 1.0f), 0xFFFFFFu);
  EXPECT_EQ(depth_to_raw(DepthFormat::X8D24Unorm, 0.5f), 8388608u);
  EXPECT_EQ(depth_to_raw(DepthFormat::X8D24Unorm, std::nextafter(0.5f, 0.0f)), 8388607u);
  EXPECT_EQ(depth_to_raw(DepthFormat::X8D24Unorm, std::nextafter(0.5f, 1.0f)), 8388608u);
}

// docs/lavapipe-rules.md §7.10: the set-up runs under FTZ/DAZ, so a gradient below 2^-126
// becomes 0. z = 1e-37, 3e-37, 5e-37 over 64 px: dz/dx = 2e-37/64 ~ 3e-39 (denormal).
TEST(CpuDepth, DenormalPlaneGradientFlushesUnderLavapipesMode) {
  const std::array<WindowVertex, 3> v = {WindowVertex{0, 0, 1e-37f}, WindowVertex{64, 0, 3e-37f},
                                         WindowVertex{0, 64, 5e-37f}};
  {
    const DenormalsFlushed ftz_daz;
    const DepthPlane plane = triangle_depth_plane(v, 0.5f);
    EXPECT_EQ(float_bits(plane.dzdx), 0u);
    EXPECT_EQ(float_bits(plane.dzdy), 0u);
    EXPECT_EQ(plane.a0, 1e-37f);
    // DAZ: a denormal depth offset reads as 0 in the per-sample add.
    EXPECT_EQ(sample_depth(plane, 1e-39f, 3, 3, DepthRange{}, DepthFormat::D32Sfloat, true).with_offset, 1e-37f);
  }
  const DenormalsKept kept;
  const DepthPlane plane = triangle_depth_plane(v, 0.5f);
  EXPECT_GT(plane.dzdx, 0.0f);
  EXPECT_LT(plane.dzdx, std::numeric_limits<float>::min());  // denormal without the mode
}

// The viewport constants are state, computed by lvp outside draw_vbo: a denormal depth range
// survives even when the caller flushes (the JIT then reads it as 0, under DAZ).
TEST(CpuDepth, ViewportConstantsKeepDenormals) {
  const DenormalsFlushed ftz_daz;
  const ViewportTransform t = make_viewport_transform(Viewport{0, 0, 4, 4, 0, 2e-39f});
  EXPECT_EQ(float_bits(t.scale[2]), float_bits(2e-39f));  // bits: a float compare would read 0 (DAZ)
  EXPECT_EQ(float_bits(t.zmax), float_bits(2e-39f));
  EXPECT_EQ(float_bits(window_from_clip_jit({0, 0, 0.5f, 1}, t, true).z), 0u);
}

TEST(CpuDepth, D32StoresTheFloatBits) {
  EXPECT_EQ(depth_to_raw(DepthFormat::D32Sfloat, 0.5f), 0x3F000000u);
  EXPECT_EQ(depth_to_raw(DepthFormat::D32Sfloat, 1.0f), 0x3F800000u);
}

TEST(CpuDepth, ClearValuesPackAsUtilPackZ) {
  EXPECT_EQ(clear_depth_raw(DepthFormat::D16Unorm, 1.0f), 0xFFFFu);
  EXPECT_EQ(clear_depth_raw(DepthFormat::D16Unorm, 0.5f), 32768u);  // lrint(32767.5): even
  EXPECT_EQ(clear_depth_raw(DepthFormat::X8D24Unorm, 0.0f), 0u);
  EXPECT_EQ(clear_depth_raw(DepthFormat::X8D24Unorm, 0.25f), 4194304u);  // lrint(4194303.75)
  EXPECT_EQ(clear_depth_raw(DepthFormat::D32Sfloat, 0.25f), 0x3E800000u);
}

// z = 0.1*x + 0.2*y + 0.3 from three vertices; the origin-based a0 includes the -0.5 centre shift.
TEST(CpuDepth, TrianglePlaneIsExtrapolatedToTheFramebufferOrigin) {
  const std::array<WindowVertex, 3> v = {WindowVertex{0, 0, 0.3f}, WindowVertex{10, 0, 1.3f},
                                         WindowVertex{0, 10, 2.3f}};
  const DepthPlane plane = triangle_depth_plane(v, 0.5f);
  EXPECT_FLOAT_EQ(plane.dzdx, 0.1f);
  EXPECT_FLOAT_EQ(plane.dzdy, 0.2f);
  EXPECT_FLOAT_EQ(plane.a0, 0.3f + 0.05f + 0.1f);  // value at pixel (0,0)'s centre (0.5, 0.5)
  EXPECT_FLOAT_EQ(interpolate_depth(plane, 2, 3, true), 0.3f + 0.1f * 2.5f + 0.2f * 3.5f);
}

std::array<WindowVertex, 3> flat_triangle(float z) {
  return {WindowVertex{0, 0, z}, WindowVertex{10, 0, z}, WindowVertex{0, 10, z}};
}

DepthBias constant_bias(float constant, float clamp = 0) { return DepthBias{true, constant, 0, clamp}; }

// r for UNORM formats is 2/(2^n - 1), formed in double and rounded once (docs/lavapipe-rules.md §4.3).
TEST(CpuDepth, BiasConstantTermPerFormat) {
  const auto o16 = triangle_depth_offset(flat_triangle(0.5f), constant_bias(1), DepthFormat::D16Unorm);
  EXPECT_EQ(o16.offset, static_cast<float>(2.0 / 65535.0));
  const auto o24 = triangle_depth_offset(flat_triangle(0.5f), constant_bias(3), DepthFormat::X8D24Unorm);
  EXPECT_EQ(o24.offset, static_cast<float>(3.0 * (1.0 / 16777215.0) * 2));
  // D32: r = 2^(e - 23) with e the exponent of the largest |z|: 0.5 and 0.75 -> 2^-24, 1 -> 2^-23.
  EXPECT_EQ(triangle_depth_offset(flat_triangle(0.5f), constant_bias(1), DepthFormat::D32Sfloat).offset,
            std::ldexp(1.0f, -24));
  EXPECT_EQ(triangle_depth_offset(flat_triangle(0.75f), constant_bias(2), DepthFormat::D32Sfloat).offset,
            std::ldexp(1.0f, -23));
  EXPECT_EQ(triangle_depth_offset(flat_triangle(1.0f), constant_bias(1), DepthFormat::D32Sfloat).offset,
            std::ldexp(1.0f, -23));
  // Biased exponent <= 23 (|z| < 2^-103), including z = 0: r = 0.
  EXPECT_EQ(triangle_depth_offset(flat_triangle(0.0f), constant_bias(1), DepthFormat::D32Sfloat).offset, 0.0f);
}

TEST(CpuDepth, BiasSlopeTermUsesTheLargerGradient) {
  const std::array<WindowVertex, 3> v = {WindowVertex{0, 0, 0}, WindowVertex{10, 0, 1}, WindowVertex{0, 10, 0.5f}};
  const DepthOffset o = triangle_depth_offset(v, DepthBias{true, 0, 2, 0}, DepthFormat::D32Sfloat);
  EXPECT_TRUE(o.computed);
  EXPECT_FLOAT_EQ(o.m, 0.1f);  // max(|0.1|, |0.05|)
  EXPECT_FLOAT_EQ(o.offset, 0.2f);
}

TEST(CpuDepth, BiasClampLimitsTheOffsetBySign) {
  const auto pos = triangle_depth_offset(flat_triangle(0.5f), constant_bias(1000, 1e-3f), DepthFormat::D16Unorm);
  EXPECT_EQ(pos.offset, 1e-3f);
  EXPECT_TRUE(pos.clamped);
  const auto neg = triangle_depth_offset(flat_triangle(0.5f), constant_bias(-1000, -1e-3f), DepthFormat::D16Unorm);
  EXPECT_EQ(neg.offset, -1e-3f);
  const auto loose = triangle_depth_offset(flat_triangle(0.5f), constant_bias(1, 1.0f), DepthFormat::D16Unorm);
  EXPECT_FALSE(loose.clamped);
}

TEST(CpuDepth, NoBiasMeansAnExactZeroOffset) {
  EXPECT_FALSE(triangle_depth_offset(flat_triangle(0.5f), DepthBias{}, DepthFormat::D16Unorm).computed);
  const auto zero = triangle_depth_offset(flat_triangle(0.5f), DepthBias{true, 0, 0, 1e-3f}, DepthFormat::D16Unorm);
  EXPECT_FALSE(zero.computed);
  EXPECT_EQ(float_bits(zero.offset), 0u);
}

// The offset is added before the [0,1] clamp, then the depth clamp applies (§3.4).
TEST(CpuDepth, SampleDepthClampsToUnitRangeThenToTheViewportRange) {
  const DepthPlane plane{0.9f, 0, 0};
  const SampleDepth d = sample_depth(plane, 0.25f, 0, 0, DepthRange{true, 0.2f, 0.6f}, DepthFormat::D32Sfloat, true);
  EXPECT_FLOAT_EQ(d.with_offset, 1.15f);
  EXPECT_EQ(d.clamped_01, 1.0f);
  EXPECT_EQ(d.depth_clamped, 0.6f);
  const SampleDepth off = sample_depth(plane, 0.25f, 0, 0, DepthRange{false, 0.2f, 0.6f}, DepthFormat::D32Sfloat, true);
  EXPECT_EQ(off.depth_clamped, 1.0f);
  // SSE min/max return the second operand for NaN: min(NaN, 1) = 1.
  const SampleDepth nan = sample_depth(DepthPlane{std::numeric_limits<float>::quiet_NaN(), 0, 0}, 0, 0, 0, DepthRange{},
                                       DepthFormat::D32Sfloat, true);
  EXPECT_EQ(nan.clamped_01, 1.0f);
}

// fma(dzdy, py, fma(dzdx, px, a0)) differs from the two-rounding evaluation when the product's
// low bits matter: a = 1 + 2^-12, a*a = 1 + 2^-11 + 2^-24 rounds (tie, even) to 1 + 2^-11, so
// a*a - 1 = 2^-11 while the fused result keeps 2^-11 + 2^-24.
TEST(CpuDepth, InterpolationFusesWhenAsked) {
  const float a = 1.0f + std::ldexp(1.0f, -12);
  const DepthPlane plane{-1.0f, a, 0};
  EXPECT_EQ(interpolate_depth(plane, a, 0, true), std::ldexp(1.0f, -11) + std::ldexp(1.0f, -24));
  EXPECT_EQ(interpolate_depth(plane, a, 0, false), std::ldexp(1.0f, -11));
}

TEST(CpuDepth, UnormCompareIsUnsigned) {
  EXPECT_TRUE(depth_test_passes(CompareOp::Less, DepthFormat::D16Unorm, 5, 6));
  EXPECT_FALSE(depth_test_passes(CompareOp::Less, DepthFormat::D16Unorm, 6, 6));
  EXPECT_TRUE(depth_test_passes(CompareOp::LessOrEqual, DepthFormat::D16Unorm, 6, 6));
  EXPECT_TRUE(depth_test_passes(CompareOp::Greater, DepthFormat::X8D24Unorm, 0xFFFFFF, 0));
  EXPECT_TRUE(depth_test_passes(CompareOp::NotEqual, DepthFormat::X8D24Unorm, 1, 2));
  EXPECT_TRUE(depth_test_passes(CompareOp::Equal, DepthFormat::X8D24Unorm, 2, 2));
  EXPECT_TRUE(depth_test_passes(CompareOp::GreaterOrEqual, DepthFormat::X8D24Unorm, 2, 2));
  EXPECT_FALSE(depth_test_passes(CompareOp::Never, DepthFormat::D16Unorm, 0, 1));
  EXPECT_TRUE(depth_test_passes(CompareOp::Always, DepthFormat::D16Unorm, 1, 0));
}

TEST(CpuDepth, FloatCompareIsUnorderedIeee) {
  const uint32_t nan = float_bits(std::numeric_limits<float>::quiet_NaN());
  const uint32_t half = float_bits(0.5f), one = float_bits(1.0f);
  EXPECT_TRUE(depth_test_passes(CompareOp::Less, DepthFormat::D32Sfloat, half, one));
  EXPECT_FALSE(depth_test_passes(CompareOp::Less, DepthFormat::D32Sfloat, one, half));
  EXPECT_TRUE(depth_test_passes(CompareOp::Less, DepthFormat::D32Sfloat, nan, half));   // ULT
  EXPECT_TRUE(depth_test_passes(CompareOp::Equal, DepthFormat::D32Sfloat, nan, half));  // UEQ
  EXPECT_TRUE(depth_test_passes(CompareOp::Equal, DepthFormat::D32Sfloat, float_bits(0.0f), float_bits(-0.0f)));
  EXPECT_FALSE(depth_test_passes(CompareOp::Never, DepthFormat::D32Sfloat, nan, half));
}

}  // namespace
}  // namespace rastercmp::cpu
