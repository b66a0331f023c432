#version 300 es
precision highp float;
// Vendored change (see web.rs, `copy_present_program`): a plain copy.
in vec2 uv;
uniform sampler2D present_texture;
out vec4 frag;
void main() {
  frag = texture(present_texture, uv);
}
