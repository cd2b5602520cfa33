// The eight-wide set-up of small triangles for AVX2 hosts (small_setup_simd.inl).
#include "cpu_raster/fast/cpu_features.hpp"

#define RASTERCMP_SMALL_TARGET RASTERCMP_AVX2
#define RASTERCMP_SMALL_SETUP setup_small_block_avx2
#define RASTERCMP_SMALL_TRAILING_PLANES trailing_depth_planes_avx2
#include "cpu_raster/fast/small_setup_simd.inl"
