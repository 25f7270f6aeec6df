#version 450
// One triangle that covers the screen (no vertex buffer); uv in [0, 1] across the screen.
layout(location = 0) out vec2 uv;
void main() {
  uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  gl_Position = vec4(uv * 2.0 - 1.0, 1.0, 1.0);  // at the far plane: props and film are drawn in front
}
