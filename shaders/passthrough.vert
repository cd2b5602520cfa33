// Pass-through vertex shader: positions arrive in clip space, computed on the host
// (docs/lavapipe-rules.md §1.7), so the driver's vertex arithmetic never touches them.
#version 450

layout(location = 0) in vec4 pos_clip;

void main() {
  gl_Position = pos_clip;
}
