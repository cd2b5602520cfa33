// Samples every texel of a single-sample depth image holding known raw values and stores the
// float the sampler returns, bit for bit, at index y * width + x: how the device converts its
// UNORM depth formats to float (vk_gather.hpp measure_unorm_sampling).
#version 450

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D depth;
layout(std430, set = 0, binding = 1) writeonly buffer Sampled {
  uint depth_bits[];
} sampled;

// The gather shaders' push constants (vk_gather.cpp GatherConstants); samples and first_row unused.
layout(push_constant) uniform GatherConstants {
  uint width;
  uint samples;
  uint first_row;
  uint rows;
} size;

void main() {
  const uvec2 texel = gl_GlobalInvocationID.xy;
  if (texel.x >= size.width || texel.y >= size.rows) return;
  sampled.depth_bits[texel.y * size.width + texel.x] = floatBitsToUint(texelFetch(depth, ivec2(texel), 0).r);
}
