// The per-frame uniform shared by every pipeline; mirrors `FrameUniforms` in
// uniforms.rs. Prepended to each shader source by the renderer.

struct Frame {
    view: mat4x4<f32>,
    projection: mat4x4<f32>,
    viewport: vec4<f32>,
};

@group(0) @binding(0) var<uniform> frame: Frame;
