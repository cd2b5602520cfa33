// The plane rows of the AVX2 exact rows (exact_rows_avx2.hpp): each plane's values, steps and
// place for the rows of a primitive's samples, plane by plane or a line's four planes at once, and
// the middle rows of a line's parallelogram, where its two long edges alone give the columns. The
// kernels that step them: exact_rows_avx2.cpp, exact_rows_4x_avx2.cpp.
#include <immintrin.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>

#include "cpu_raster/fast/cpu_features.hpp"
#include "cpu_raster/fast/exact_rows_avx2.hpp"

namespace rastercmp::cpu::fast {

namespace {

// The bounds of init_plane_rows' checks, which themselves stay inside int64: |dcdx|, |dcdy| <= 2^30
// and the widest column |x| + 2 <= 2^20, so that |d| * widest (d = dcdx * 256) does.
constexpr int64_t kDeltaBound = int64_t(1) << 30;
constexpr int64_t kWidestBound = int64_t(1) << 20;

// The largest |x| of p's visit columns, plus the two columns past them that the steps test.
inline int64_t widest_column(const RasterPrimitive& p) {
  return std::max<int64_t>(std::abs(int64_t(p.visit.x0)), std::abs(int64_t(p.visit.x1))) + 2;
}

}  // namespace

// exact_rows_avx2.hpp.
RASTERCMP_AVX2 bool init_plane_rows_each(PlaneRows& rows, const RasterPrimitive& p, uint32_t samples, int32_t y0,
                                         int32_t y1) {
  const int64_t widest = widest_column(p);
  if (widest > kWidestBound) return false;
  const int64_t span = (int64_t(y1) + 3 - y0) * kFixedOne;
  uint32_t below = 0, above = 0;  // planes bounding the columns below (d < 0), above (d > 0): bit i
  for (uint32_t i = 0; i < p.planes.count; ++i) {
    const EdgePlane& plane = p.planes.plane[i];
    if (plane.dcdx > kDeltaBound || plane.dcdx < -kDeltaBound || plane.dcdy > kDeltaBound || plane.dcdy < -kDeltaBound)
      return false;
    const int64_t d = plane.dcdx * kFixedOne;
    if ((d < 0 ? -d : d) * widest > kExactBound) return false;
    below |= uint32_t(d < 0) << i;
    above |= uint32_t(d > 0) << i;
  }
  const uint32_t flat = ((1u << p.planes.count) - 1) & ~(below | above);
  int64_t sample_x[4], sample_y[4];  // sample_point(0, y0, s, p.per_sample)'s fixed coordinates
  for (uint32_t s = 0; s < samples; ++s) {
    sample_x[s] = p.per_sample ? kStandardSamples4x[s].x_fixed : 0;
    sample_y[s] = int64_t(y0) * kFixedOne + (p.per_sample ? kStandardSamples4x[s].y_fixed : 0);
  }
  rows.lower = uint32_t(std::popcount(below));
  rows.upper = rows.lower + uint32_t(std::popcount(above));
  rows.count = p.planes.count;
  for (uint32_t i = 0; i < p.planes.count; ++i) {
    // plane i's place: its group's start plus the planes of its group before it
    const uint32_t before = (1u << i) - 1;
    const uint32_t e = (below >> i & 1)   ? uint32_t(std::popcount(below & before))
                       : (above >> i & 1) ? rows.lower + uint32_t(std::popcount(above & before))
                                          : rows.upper + uint32_t(std::popcount(flat & before));
    const EdgePlane& plane = p.planes.plane[i];
    for (uint32_t s = 0; s < samples; ++s) {
      const int64_t first = edge_value(plane, sample_x[s], sample_y[s]) - 1;
      const int64_t last = first + plane.dcdy * span;
      if (first > kExactBound || first < -kExactBound || last > kExactBound || last < -kExactBound) return false;
      rows.first[s][e] = double(first);  // exact integers, as every value below
    }
    rows.dy[e] = double(plane.dcdy * kFixedOne);
    rows.step[e] = _mm256_set1_pd(4.0 * rows.dy[e]);
    const double gx = -double(plane.dcdx * kFixedOne);
    rows.gx[e] = _mm256_set1_pd(gx);
    rows.inv[e] = _mm256_set1_pd(gx != 0 ? -1.0 / gx : 0.0);
  }
  return true;
}

namespace {

// Four planes' places by group (init_plane_rows_each's order: the planes bounding below in plane
// order, then those bounding above, then the flat ones), indexed by below | above << 4 (bit i: plane
// i): the plane at place e in bits 2e and 2e + 1.
constexpr std::array<uint8_t, 256> four_plane_places() {
  std::array<uint8_t, 256> places{};
  for (uint32_t below = 0; below < 16; ++below) {
    for (uint32_t above = 0; above < 16; ++above) {
      if ((below & above) != 0) continue;
      uint32_t order = 0, e = 0;
      for (const uint32_t group : {below, above, 15u & ~(below | above)})
        for (uint32_t i = 0; i < 4; ++i)
          if (group >> i & 1) order |= i << (2 * e++);
      places[below | above << 4] = uint8_t(order);
    }
  }
  return places;
}
constexpr std::array<uint8_t, 256> kFourPlanePlaces = four_plane_places();

// int64 lanes in [-2^51, 2^51) as doubles, exactly: 2^52 + 2^51 + v has v in its low mantissa bits.
RASTERCMP_AVX2 inline __m256d exact_doubles(__m256i v) {
  const __m256d magic = _mm256_set1_pd(0x1.8p52);
  return _mm256_sub_pd(_mm256_castsi256_pd(_mm256_add_epi64(v, _mm256_castpd_si256(magic))), magic);
}

// out[e] = lane e of v in every lane, e = 0..3.
RASTERCMP_AVX2 inline void broadcast_lanes(__m256d v, __m256d* out) {
  out[0] = _mm256_permute4x64_pd(v, 0x00);
  out[1] = _mm256_permute4x64_pd(v, 0x55);
  out[2] = _mm256_permute4x64_pd(v, 0xAA);
  out[3] = _mm256_permute4x64_pd(v, 0xFF);
}

// The four 64-bit lanes of v in the order `index` gives (two dword indices a lane).
RASTERCMP_AVX2 inline __m256d placed(__m256d v, __m256i index) {
  return _mm256_castsi256_pd(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(v), index));
}

}  // namespace

// init_plane_rows_each for four planes and one sample, the planes in the lanes of a vector: the
// same checks, with |first| and |last| below 2^51 and y0, the rows' span within int32 (so that the
// products are _mm256_mul_epi32's and the conversions exact_doubles'), and the same values (each
// an exact integer, or the same IEEE operation: 4 * dy, -double(d), -1 / gx). false where any
// check fails: init_plane_rows_each then decides, as before.
RASTERCMP_AVX2 bool init_four_plane_rows(PlaneRows& rows, const RasterPrimitive& p, int32_t y0, int32_t y1) {
  const int64_t widest = widest_column(p);
  const int64_t sample_x = p.per_sample ? kStandardSamples4x[0].x_fixed : 0;
  const int64_t sample_y = int64_t(y0) * kFixedOne + (p.per_sample ? kStandardSamples4x[0].y_fixed : 0);
  const int64_t span = (int64_t(y1) + 3 - y0) * kFixedOne;
  constexpr int64_t kInt32 = int64_t(1) << 31;
  if (widest > kWidestBound || sample_y >= kInt32 || sample_y < -kInt32 || span >= kInt32 || span < -kInt32)
    return false;
  const EdgePlane* e = p.planes.plane.data();
  const __m256i c = _mm256_setr_epi64x(e[0].c, e[1].c, e[2].c, e[3].c);
  const __m256i dcdx = _mm256_setr_epi64x(e[0].dcdx, e[1].dcdx, e[2].dcdx, e[3].dcdx);
  const __m256i dcdy = _mm256_setr_epi64x(e[0].dcdy, e[1].dcdy, e[2].dcdy, e[3].dcdy);
  const __m256i delta_bound = _mm256_set1_epi64x(kDeltaBound), low_delta = _mm256_set1_epi64x(-kDeltaBound);
  __m256i bad =
      _mm256_or_si256(_mm256_or_si256(_mm256_cmpgt_epi64(dcdx, delta_bound), _mm256_cmpgt_epi64(low_delta, dcdx)),
                      _mm256_or_si256(_mm256_cmpgt_epi64(dcdy, delta_bound), _mm256_cmpgt_epi64(low_delta, dcdy)));
  // |dcdx| * 256 * widest (< 2^59 where |dcdx| <= 2^30; a lane past that is bad already)
  const __m256i zero = _mm256_setzero_si256();
  const __m256i abs_dcdx = _mm256_castpd_si256(_mm256_blendv_pd(
      _mm256_castsi256_pd(dcdx), _mm256_castsi256_pd(_mm256_sub_epi64(zero, dcdx)), _mm256_castsi256_pd(dcdx)));
  const __m256i reach = _mm256_mul_epu32(abs_dcdx, _mm256_set1_epi64x(widest * kFixedOne));
  const __m256i exact_bound = _mm256_set1_epi64x(kExactBound), low_bound = _mm256_set1_epi64x(-kExactBound);
  bad = _mm256_or_si256(bad, _mm256_cmpgt_epi64(reach, exact_bound));
  // edge_value(plane, sample_x, sample_y) - 1 and its value `span` rows on; below 2^51 in magnitude
  const __m256i first =
      _mm256_sub_epi64(_mm256_add_epi64(c, _mm256_sub_epi64(_mm256_mul_epi32(dcdy, _mm256_set1_epi64x(sample_y)),
                                                            _mm256_mul_epi32(dcdx, _mm256_set1_epi64x(sample_x)))),
                       _mm256_set1_epi64x(1));
  const __m256i last = _mm256_add_epi64(first, _mm256_mul_epi32(dcdy, _mm256_set1_epi64x(span)));
  const __m256i below_limit = _mm256_sub_epi64(exact_bound, _mm256_set1_epi64x(1));  // 2^51 - 1
  bad = _mm256_or_si256(bad,
                        _mm256_or_si256(_mm256_cmpgt_epi64(first, below_limit), _mm256_cmpgt_epi64(low_bound, first)));
  bad =
      _mm256_or_si256(bad, _mm256_or_si256(_mm256_cmpgt_epi64(last, below_limit), _mm256_cmpgt_epi64(low_bound, last)));
  if (!_mm256_testz_si256(bad, bad)) return false;
  const uint32_t below = uint32_t(_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpgt_epi64(zero, dcdx))));
  const uint32_t above = uint32_t(_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpgt_epi64(dcdx, zero))));
  rows.lower = uint32_t(std::popcount(below));
  rows.upper = rows.lower + uint32_t(std::popcount(above));
  rows.count = 4;
  // the lanes in their places: place e takes plane (places >> 2e) & 3, two dwords a lane
  const __m256i places = _mm256_set1_epi32(kFourPlanePlaces[below | above << 4]);
  const __m256i plane =
      _mm256_and_si256(_mm256_srlv_epi32(places, _mm256_setr_epi32(0, 0, 2, 2, 4, 4, 6, 6)), _mm256_set1_epi32(3));
  const __m256i index = _mm256_add_epi32(_mm256_add_epi32(plane, plane), _mm256_setr_epi32(0, 1, 0, 1, 0, 1, 0, 1));
  const __m256d dy = placed(exact_doubles(_mm256_slli_epi64(dcdy, kFixedOrder)), index);  // dcdy * 256
  // gx = -double(dcdx * 256) (-0 for a flat plane, as there), inv = -1 / gx or 0
  const __m256d gx =
      placed(_mm256_xor_pd(exact_doubles(_mm256_slli_epi64(dcdx, kFixedOrder)), _mm256_set1_pd(-0.0)), index);
  const __m256d flat = _mm256_cmp_pd(gx, _mm256_setzero_pd(), _CMP_EQ_OQ);
  const __m256d inv =
      _mm256_andnot_pd(flat, _mm256_div_pd(_mm256_set1_pd(-1.0), _mm256_blendv_pd(gx, _mm256_set1_pd(1.0), flat)));
  const __m256d step = _mm256_mul_pd(_mm256_set1_pd(4.0), dy);
  _mm256_storeu_pd(rows.first[0], placed(exact_doubles(first), index));
  _mm256_storeu_pd(rows.dy, dy);
  broadcast_lanes(step, rows.step);
  broadcast_lanes(gx, rows.gx);
  broadcast_lanes(inv, rows.inv);
  return true;
}

// exact_rows_avx2.hpp.
RASTERCMP_AVX2 ParallelogramMiddle parallelogram_middle(const RasterPrimitive& p, const PlaneRows& rows) {
  ParallelogramMiddle middle;
  if (!p.is_line || p.per_sample || p.binned || p.edge_count != 4 || rows.count != 4) return middle;
  const EdgePlane* e = p.planes.plane.data();
  const std::array<FixedPoint, 4>& v = p.vertex_fixed;
  if (v[0].x.wide() + v[2].x.wide() != v[1].x.wide() + v[3].x.wide() ||
      v[0].y.wide() + v[2].y.wide() != v[1].y.wide() + v[3].y.wide() || e[0].dcdx == 0)
    return middle;  // not a parallelogram, or a flat long edge (the caps then span its rows)
  // the caps' y ranges: edge 1 from corner 1 to 2, edge 3 from corner 3 to 0
  const int64_t a_lo = std::min(v[1].y.wide(), v[2].y.wide()), a_hi = std::max(v[1].y.wide(), v[2].y.wide());
  const int64_t b_lo = std::min(v[3].y.wide(), v[0].y.wide()), b_hi = std::max(v[3].y.wide(), v[0].y.wide());
  const bool a_below = a_hi < b_lo;
  if (!a_below && !(b_hi < a_lo)) return middle;
  const int64_t below = a_below ? a_hi : b_hi, above = a_below ? b_lo : a_lo;  // 24.8, within int32
  // sample rows py with below < py * 256 < above (row py's pixel centre is at py * 256)
  middle.first_row = int32_t((below >> kFixedOrder) + 1);
  middle.last_row = int32_t(-((-above) >> kFixedOrder) - 1);
  // the long edges' places, init_plane_rows' (kFourPlanePlaces' order)
  uint32_t below_planes = 0, above_planes = 0;
  for (uint32_t i = 0; i < 4; ++i) {
    below_planes |= uint32_t(e[i].dcdx < 0) << i;
    above_planes |= uint32_t(e[i].dcdx > 0) << i;
  }
  const uint32_t order = kFourPlanePlaces[below_planes | above_planes << 4];
  const uint32_t long_below = e[0].dcdx < 0 ? 0 : 2;  // the long edge bounding below; the other above
  for (uint32_t place = 0; place < 4; ++place) {
    const uint32_t plane = order >> (2 * place) & 3;
    if (plane == long_below) middle.lower = place;
    if (plane == 2 - long_below) middle.upper = place;
  }
  return middle;
}

RASTERCMP_AVX2 bool init_plane_rows(PlaneRows& rows, const RasterPrimitive& p, uint32_t samples, int32_t y0,
                                    int32_t y1) {
  if (p.planes.count == 4 && samples == 1 && init_four_plane_rows(rows, p, y0, y1)) return true;
  return init_plane_rows_each(rows, p, samples, y0, y1);
}

}  // namespace rastercmp::cpu::fast
