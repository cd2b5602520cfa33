// Owner id of every fragment: (draw index << 24) | primitive index within the draw
// (model/render_result.hpp encode_owner). gl_PrimitiveID needs the geometryShader feature.
#version 450

layout(push_constant) uniform DrawConstants {
  uint draw_index;
} draw_constants;

layout(location = 0) out uint owner;

void main() {
  owner = (draw_constants.draw_index << 24) | (uint(gl_PrimitiveID) & 0x00FFFFFFu);
}
