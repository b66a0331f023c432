#version 300 es
precision highp float;
// Vendored change (see web.rs, `copy_present_program`): a triangle that covers
// the whole screen; the top of the screen shows texture row 0 (wgpu draws
// flipped, like the sRGB present and the blit it replaces).
out vec2 uv;
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  uv = vec2(p.x * 0.5 + 0.5, 0.5 - p.y * 0.5);
  gl_Position = vec4(p, 0.0, 1.0);
}
