// Snapping to 24.8 fixed point (docs/lavapipe-rules.md §2.2, §5.3), with answers worked out by hand.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "cpu_raster/exact/fixed_point.hpp"

namespace rastercmp::cpu {
namespace {

constexpr float kHalf = 0.5f;  // single-sample pixel offset

int32_t snap(float x, SnapRounding rounding, float offset = kHalf) {
  const auto fixed = snap_vertex(x, offset, rounding);
  EXPECT_TRUE(fixed.has_value()) << x;
  return fixed ? fixed->raw : 0;
}

// fl(x - 0.5) * 256 lands exactly on k + 0.5 for x = 0.5 + (2k+1)/512: round-to-nearest-even
// picks the even neighbour, round-half-away the one further from zero.
TEST(CpuSnap, TiesAtOddMultiplesOfHalfASubpixelRoundToEven) {
  EXPECT_EQ(snap(0.5f + 1.0f / 512, SnapRounding::NearestEven), 0);   // 0.5 -> 0
  EXPECT_EQ(snap(0.5f + 3.0f / 512, SnapRounding::NearestEven), 2);   // 1.5 -> 2
  EXPECT_EQ(snap(0.5f + 5.0f / 512, SnapRounding::NearestEven), 2);   // 2.5 -> 2
  EXPECT_EQ(snap(0.5f - 1.0f / 512, SnapRounding::NearestEven), 0);   // -0.5 -> -0
  EXPECT_EQ(snap(0.5f - 3.0f / 512, SnapRounding::NearestEven), -2);  // -1.5 -> -2
}

// round_nearest_even is std::nearbyint (default rounding mode) for every float kind: ties around
// zero, 2^22 and 2^23, the last fractions below 2^23, signed zeros, denormals, Inf, NaN, and a
// million random bit patterns (every exponent).
TEST(CpuSnap, NearestEvenRoundingIsNearbyint) {
  const auto same = [](float v) {
    const float want = std::nearbyint(v), got = round_nearest_even(v);
    if (std::isnan(want)) return std::isnan(got);
    return std::bit_cast<uint32_t>(want) == std::bit_cast<uint32_t>(got);
  };
  const float two23 = 8388608.0f, inf = std::numeric_limits<float>::infinity();
  const float ties[] = {0.5f, -0.5f, 1.5f, -1.5f, 2.5f, -2.5f, 4194304.5f, -4194303.5f, two23 - 0.5f, -(two23 - 0.5f)};
  const float bounds[] = {0.0f, -0.0f, 0.49999997f, -0.49999997f, two23, two23 + 1, -two23 - 2};
  const float odd[] = {1e-45f, -1e-45f, 1e-38f, inf, -inf, std::nanf(""), std::nextafter(two23, 0.0f)};
  std::vector<float> values(std::begin(ties), std::end(ties));
  values.insert(values.end(), std::begin(bounds), std::end(bounds));
  values.insert(values.end(), std::begin(odd), std::end(odd));
  std::mt19937 rng(7);
  for (int i = 0; i < 1000000; ++i) values.push_back(std::bit_cast<float>(uint32_t(rng())));
  for (int i = 0; i < 100000; ++i)
    values.push_back(float(int32_t(rng() % 20000000) - 10000000) * 0.25f);  // quarters: ties
  int wrong = 0;
  for (float v : values) wrong += same(v) ? 0 : 1;
  EXPECT_EQ(wrong, 0);
  EXPECT_TRUE(same(0.5f) && std::bit_cast<uint32_t>(round_nearest_even(-0.25f)) == 0x80000000u);  // -0
}

TEST(CpuSnap, RoundHalfAwayMovesTiesAwayFromZero) {
  EXPECT_EQ(snap(0.5f + 1.0f / 512, SnapRounding::HalfAwayFromZero), 1);
  EXPECT_EQ(snap(0.5f + 3.0f / 512, SnapRounding::HalfAwayFromZero), 2);
  EXPECT_EQ(snap(0.5f + 5.0f / 512, SnapRounding::HalfAwayFromZero), 3);
  EXPECT_EQ(snap(0.5f - 1.0f / 512, SnapRounding::HalfAwayFromZero), -1);
  EXPECT_EQ(snap(0.5f - 3.0f / 512, SnapRounding::HalfAwayFromZero), -2);
}

TEST(CpuSnap, PixelCentreIsTheOriginOfTheSingleSampleFrame) {
  EXPECT_EQ(snap(0.5f, SnapRounding::NearestEven), 0);
  EXPECT_EQ(snap(3.5f, SnapRounding::NearestEven), 3 * 256);
  EXPECT_EQ(snap(3.0f, SnapRounding::NearestEven), 3 * 256 - 128);
  EXPECT_EQ(snap(3.0f + 1.0f / 256, SnapRounding::NearestEven), 3 * 256 - 127);
}

TEST(CpuSnap, MultisampleFrameHasNoHalfPixelOffset) {
  EXPECT_EQ(snap(3.0f, SnapRounding::NearestEven, 0.0f), 3 * 256);
  EXPECT_EQ(snap(1.0f / 512, SnapRounding::NearestEven, 0.0f), 0);
  EXPECT_EQ(snap(3.0f / 512, SnapRounding::NearestEven, 0.0f), 2);
}

TEST(CpuSnap, NonFiniteAndOutOfRangeCoordinatesDoNotSnap) {
  EXPECT_FALSE(snap_vertex(std::numeric_limits<float>::quiet_NaN(), kHalf, SnapRounding::NearestEven));
  EXPECT_FALSE(snap_vertex(std::numeric_limits<float>::infinity(), kHalf, SnapRounding::NearestEven));
  EXPECT_FALSE(snap_vertex(-1e30f, kHalf, SnapRounding::NearestEven));
  // The bound is 2^25 fixed units = 131072 px; 49152 px (the far end of viewportBoundsRange plus
  // the largest viewport) snaps.
  EXPECT_TRUE(snap_vertex(49152.0f, kHalf, SnapRounding::NearestEven));
  EXPECT_FALSE(snap_vertex(131073.0f, kHalf, SnapRounding::NearestEven));
}

// util_iround adds ±0.5 in float and truncates: 2.5 -> 3, -2.5 -> -3, and 0.49999997 (0.5 - 2^-25)
// + 0.5 rounds to 1.0f, so it gives 1 where exact rounding gives 0.
TEST(CpuSnap, UtilIroundRoundsHalfAwayAfterAFloatAdd) {
  EXPECT_EQ(util_iround(2.5f), 3);
  EXPECT_EQ(util_iround(-2.5f), -3);
  EXPECT_EQ(util_iround(2.4f), 2);
  EXPECT_EQ(util_iround(-2.4f), -2);
  EXPECT_EQ(util_iround(std::nextafter(0.5f, 0.0f)), 1);
  EXPECT_EQ(util_iround(std::nextafter(-0.5f, 0.0f)), -1);
  EXPECT_FALSE(util_iround(std::numeric_limits<float>::quiet_NaN()));
}

TEST(CpuSnap, LineSnapScalesBy256First) {
  EXPECT_EQ(line_snap(1.0f), 256);
  EXPECT_EQ(line_snap(-0.5f), -128);
  EXPECT_EQ(line_snap(1.0f / 512), 1);  // 0.5 -> 1 (half away)
  EXPECT_EQ(line_snap(-1.0f / 512), -1);
}

}  // namespace
}  // namespace rastercmp::cpu
