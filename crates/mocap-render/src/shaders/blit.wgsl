// Copies a finished frame (a RenderTarget's colour texture) onto the viewport of
// another pass: one triangle covering the viewport, one nearest-filtered texel
// per pixel, no blending. `fs_copy` keeps the stored values (targets that store
// what they are given); `fs_decode` turns sRGB-encoded values into linear ones
// for an sRGB target, which encodes them again.

@group(0) @binding(0) var frame_texture: texture_2d<f32>;
@group(0) @binding(1) var frame_sampler: sampler;

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32) -> Out {
    // (-1,-1), (3,-1), (-1,3): one triangle over the whole viewport.
    let x = f32((vertex << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(vertex & 2u) * 2.0 - 1.0;
    var out: Out;
    out.position = vec4<f32>(x, y, 0.0, 1.0);
    // Texture rows run down while clip-space y runs up.
    out.uv = vec2<f32>(x * 0.5 + 0.5, 0.5 - y * 0.5);
    return out;
}

@fragment
fn fs_copy(in: Out) -> @location(0) vec4<f32> {
    return vec4<f32>(textureSampleLevel(frame_texture, frame_sampler, in.uv, 0.0).rgb, 1.0);
}

@fragment
fn fs_decode(in: Out) -> @location(0) vec4<f32> {
    let c = textureSampleLevel(frame_texture, frame_sampler, in.uv, 0.0).rgb;
    let lower = c / 12.92;
    let higher = pow((c + vec3<f32>(0.055)) / 1.055, vec3<f32>(2.4));
    return vec4<f32>(select(higher, lower, c <= vec3<f32>(0.04045)), 1.0);
}
