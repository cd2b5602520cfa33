// The eight-wide set-up of small triangles for AVX-512 hosts (small_setup_simd.inl): the same
// 256-bit intrinsics with 32 vector registers.
#include "cpu_raster/fast/cpu_features.hpp"

#define RASTERCMP_SMALL_TARGET RASTERCMP_AVX512
#define RASTERCMP_SMALL_SETUP setup_small_block_avx512
#include "cpu_raster/fast/small_setup_simd.inl"
