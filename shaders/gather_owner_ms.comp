// Copies every sample of the multisampled owner attachment into a buffer laid out as
// index = (y * width + x) * samples + sample (model/render_result.hpp).
// One invocation per pixel, all of its samples. The buffer is bound one band of rows at a time
// (maxStorageBufferRange), so the index is relative to the band's first row.
#version 450

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform usampler2DMS owner_ms;
layout(std430, set = 0, binding = 1) writeonly buffer OwnerSamples {
  uint owner[];
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
    band_samples.owner[first + s] = texelFetch(owner_ms, pixel, int(s)).r;
  }
}
