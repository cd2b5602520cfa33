// Pass-through vertex shader for point primitives (point_list topology or polygon mode point):
// as passthrough.vert, plus the point size Vulkan requires a point-drawing shader to write.
#version 450

layout(location = 0) in vec4 pos_clip;

void main() {
  gl_Position = pos_clip;
  gl_PointSize = 1.0;
}
