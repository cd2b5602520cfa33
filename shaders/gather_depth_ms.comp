// Copies every sample of the multisampled depth attachment into a buffer laid out as
// index = (y * width + x) * samples + sample (model/render_result.hpp), as the float the sampler
// returns, bit for bit: the host turns it back into the stored raw bits (vk_translate.hpp,
// depth_raw_from_sampled). Same banding and push constants as gather_owner_ms.comp.
#version 450

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2DMS depth_ms;
layout(std430, set = 0, binding = 1) writeonly buffer DepthSamples {
  uint depth_bits[];
} band_samples;

layout(push_constant) uniform GatherConstants {
  uint width;
  uint samples;
  uint first_row;
  uint rows;
} gather;

void main() {
  const uvec2 in_band = gl_GlobalInvocationID.xy;
  if (in_band.x >= gather.width || in_band.y >= gather.rows) return;
  const ivec2 pixel = ivec2(in_band.x, in_band.y + gather.first_row);
  const uint first = (in_band.y * gather.width + in_band.x) * gather.samples;
  for (uint s = 0; s < gather.samples; ++s) {
    band_samples.depth_bits[first + s] = floatBitsToUint(texelFetch(depth_ms, pixel, int(s)).r);
  }
}
