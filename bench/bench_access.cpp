// Google Benchmark binary rastercmp_bench_access: what the attachment accesses of a thin line cost
// by kind and row pitch, outside the renderer (docs/performance.md, "Lines and multisampled
// frames"). It models thin_rows' gathered step (cpu_raster/fast/exact_rows_avx2.cpp): four rows
// of two columns each, one row after another down a steep line, the stored depth read, compared
// with a new value that passes about half the time, and the passing pixels' depth and owner
// written. 20,000 such lines start at random places in two 32-bit attachments of `pitch` words a
// row and 1,024 rows (8 MiB together, as lines_20k's), each `rows` rows long.
//   Access/<kind>/pitch:<p>/rows:<r>   the time of one pass over the lines (manual time, the
//                                      attachments refilled with random depths before each pass,
//                                      untimed); counter per_step: that time per step of four rows
// Kinds: scatter (the stored depths gathered, the passing lanes scattered: thin_rows on AVX-512
// hosts), gather_only (the reads alone), blended (gathered, every lane stored back one by one,
// failing ones with what they held: thin_rows on AVX2 hosts), pairs (each row's two pixels read
// and written as one 64-bit word of each attachment, blended), records (the attachments
// interleaved, each pixel's depth and owner side by side, a row's two pixels read and written as
// one 16-byte record, blended: the same bytes in one cache line a row instead of two). With a
// pitch of 1,024 words a steep line's rows are 4 KiB apart (8 KiB for records) and fall in one
// set of the L1 data cache; 1,040 spreads them.
#include <benchmark/benchmark.h>
#include <immintrin.h>

#include <bit>
#include <chrono>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "cpu_raster/fast/cpu_features.hpp"

namespace rastercmp {
namespace {

enum class Kind { Scatter, GatherOnly, Blended, Pairs, Records };

constexpr int32_t kLines = 20000, kHeight = 1024;

struct Attachments {
  std::vector<uint32_t> depth, owner;
  std::vector<int32_t> column, row;  // each line's first pixel
};

// The passing lanes' writes of the scatter kind (AVX-512 hosts: exact_rows_avx2.cpp's
// scatter_passing).
RASTERCMP_AVX512 void scatter_passing(uint32_t* depth, uint32_t* owner, __m256i index, __m256i passes, __m256i raw,
                                      __m256i id) {
  const __mmask8 lanes = _mm256_movepi32_mask(passes);
  _mm256_mask_i32scatter_epi32(depth, lanes, index, raw, 4);
  _mm256_mask_i32scatter_epi32(owner, lanes, index, id, 4);
}

// One pass over every line; the value each step tests varies with the line, the step and `pass`.
// The count of passing lanes the gathered-only kind found (which keeps its gathers).
RASTERCMP_AVX2 uint32_t draw_lines(Kind kind, Attachments& a, int32_t pitch, int32_t rows, uint32_t pass) {
  uint32_t passing = 0;
  const __m256i lane_row = _mm256_setr_epi32(0, 0, 1, 1, 2, 2, 3, 3),
                lane_column = _mm256_setr_epi32(0, 1, 0, 1, 0, 1, 0, 1);
  const __m256i id = _mm256_set1_epi32(7);
  uint32_t* depth = a.depth.data();
  uint32_t* owner = a.owner.data();
  for (int32_t l = 0; l < kLines; ++l) {
    for (int32_t s = 0; s < rows / 4; ++s) {
      // a steep line: one column to the right every other step
      const __m256i row = _mm256_add_epi32(_mm256_set1_epi32(a.row[size_t(l)] + 4 * s), lane_row);
      const __m256i column = _mm256_add_epi32(_mm256_set1_epi32(a.column[size_t(l)] + s / 2), lane_column);
      const __m256i index = _mm256_add_epi32(_mm256_mullo_epi32(row, _mm256_set1_epi32(pitch)), column);
      const uint32_t value = (uint32_t(l) * 2654435761u + uint32_t(s) * 40503u + pass * 9973u) & 0x3FFFFFFFu;
      const __m256i raw = _mm256_set1_epi32(int32_t(value));
      if (kind == Kind::Records) {
        // each pixel's depth and owner side by side (a.depth holds both): a row's two pixels are
        // one 16-byte record, so one cache line a row instead of one in each attachment
        alignas(16) int32_t at[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(at), index);
        float* record[4];
        for (int k = 0; k < 4; ++k) record[k] = reinterpret_cast<float*>(depth + 2 * size_t(at[2 * k]));
        // rows 0 and 2 in one register, 1 and 3 in the other: the shuffles give lane 2k + j
        const __m256 even = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(record[0])),
                                                 _mm_loadu_ps(record[2]), 1);
        const __m256 odd = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(record[1])),
                                                _mm_loadu_ps(record[3]), 1);
        const __m256i stored = _mm256_castps_si256(_mm256_shuffle_ps(even, odd, 0x88));
        const __m256i held = _mm256_castps_si256(_mm256_shuffle_ps(even, odd, 0xDD));
        const __m256i passes = _mm256_cmpgt_epi32(stored, raw);
        const __m256 new_depth = _mm256_castsi256_ps(_mm256_blendv_epi8(stored, raw, passes));
        const __m256 new_owner = _mm256_castsi256_ps(_mm256_blendv_epi8(held, id, passes));
        const __m256 rows_02 = _mm256_unpacklo_ps(new_depth, new_owner);
        const __m256 rows_13 = _mm256_unpackhi_ps(new_depth, new_owner);
        _mm_storeu_ps(record[0], _mm256_castps256_ps128(rows_02));
        _mm_storeu_ps(record[2], _mm256_extractf128_ps(rows_02, 1));
        _mm_storeu_ps(record[1], _mm256_castps256_ps128(rows_13));
        _mm_storeu_ps(record[3], _mm256_extractf128_ps(rows_13, 1));
        continue;
      }
      if (kind == Kind::Pairs) {
        alignas(16) int32_t at[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(at), index);
        uint64_t* d[4];
        uint64_t* o[4];
        for (int k = 0; k < 4; ++k) {
          d[k] = reinterpret_cast<uint64_t*>(depth + at[2 * k]);
          o[k] = reinterpret_cast<uint64_t*>(owner + at[2 * k]);
        }
        const __m256i stored = _mm256_setr_epi64x(int64_t(*d[0]), int64_t(*d[1]), int64_t(*d[2]), int64_t(*d[3]));
        const __m256i held = _mm256_setr_epi64x(int64_t(*o[0]), int64_t(*o[1]), int64_t(*o[2]), int64_t(*o[3]));
        const __m256i passes = _mm256_cmpgt_epi32(stored, raw);
        alignas(32) uint64_t depth_out[4], owner_out[4];
        _mm256_store_si256(reinterpret_cast<__m256i*>(depth_out), _mm256_blendv_epi8(stored, raw, passes));
        _mm256_store_si256(reinterpret_cast<__m256i*>(owner_out), _mm256_blendv_epi8(held, id, passes));
        for (int k = 0; k < 4; ++k) {
          *d[k] = depth_out[k];
          *o[k] = owner_out[k];
        }
        continue;
      }
      const __m256i stored = _mm256_i32gather_epi32(reinterpret_cast<const int*>(depth), index, 4);
      const __m256i passes = _mm256_cmpgt_epi32(stored, raw);
      if (kind == Kind::GatherOnly) {
        passing += uint32_t(std::popcount(uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(passes)))));
      } else if (kind == Kind::Scatter) {
        scatter_passing(depth, owner, index, passes, raw, id);
      } else {  // Blended
        const __m256i held = _mm256_i32gather_epi32(reinterpret_cast<const int*>(owner), index, 4);
        alignas(32) int32_t at[8];
        alignas(32) uint32_t depth_out[8], owner_out[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(at), index);
        _mm256_store_si256(reinterpret_cast<__m256i*>(depth_out), _mm256_blendv_epi8(stored, raw, passes));
        _mm256_store_si256(reinterpret_cast<__m256i*>(owner_out), _mm256_blendv_epi8(held, id, passes));
        for (int k = 0; k < 8; ++k) {
          depth[at[k]] = depth_out[k];
          owner[at[k]] = owner_out[k];
        }
      }
    }
  }
  return passing;
}

void access(benchmark::State& state, Kind kind) {
  if (!cpu::fast::host_has_avx2_fma()) return state.SkipWithError("needs AVX2 and FMA");
  if (kind == Kind::Scatter && !cpu::fast::host_has_avx512())
    return state.SkipWithError("the scatter needs AVX-512 (F, VL, BW, DQ)");
  const int32_t pitch = int32_t(state.range(0)), rows = int32_t(state.range(1));
  Attachments a;
  // a line's columns stay below pitch - rows + rows / 8; records: both values in a.depth
  a.depth.resize(size_t(pitch) * kHeight * (kind == Kind::Records ? 2 : 1));
  a.owner.resize(kind == Kind::Records ? 0 : a.depth.size());
  std::mt19937 rng(1);
  for (int32_t l = 0; l < kLines; ++l) {
    a.column.push_back(int32_t(rng() % uint32_t(pitch - rows)));
    a.row.push_back(int32_t(rng() % uint32_t(kHeight - rows)));
  }
  uint32_t pass = 0;
  for (auto _ : state) {
    for (uint32_t& d : a.depth) d = rng() & 0x3FFFFFFFu;
    const auto start = std::chrono::steady_clock::now();
    uint32_t passing = draw_lines(kind, a, pitch, rows, pass++);
    benchmark::DoNotOptimize(passing);  // a non-const lvalue: the overload no release deprecates
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(seconds);
  }
  // seconds per step of four rows
  state.counters["per_step"] = benchmark::Counter(
      double(kLines) * double(rows / 4), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void register_kind(const char* name, Kind kind) {
  benchmark::RegisterBenchmark((std::string("Access/") + name).c_str(), access, kind)
      ->ArgNames({"pitch", "rows"})
      ->ArgsProduct({{1024, 1040}, {8, 40}})
      ->Unit(benchmark::kMillisecond)
      ->UseManualTime();
}

}  // namespace
}  // namespace rastercmp

int main(int argc, char** argv) {
  using rastercmp::Kind;
  rastercmp::register_kind("scatter", Kind::Scatter);
  rastercmp::register_kind("gather_only", Kind::GatherOnly);
  rastercmp::register_kind("blended", Kind::Blended);
  rastercmp::register_kind("pairs", Kind::Pairs);
  rastercmp::register_kind("records", Kind::Records);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
