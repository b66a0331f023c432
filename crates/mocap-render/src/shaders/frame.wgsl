// The per-frame uniform shared by every pipeline; mirrors `FrameUniforms` in
// uniforms.rs. Prepended to each shader source by the renderer.

struct Frame {
    view: mat4x4<f32>,
    projection: mat4x4<f32>,
    // Viewport width and height in pixels; unused (sRGB encoding is the
    // ENCODE_SRGB constant); shadow strength (0 = no shadows).
    viewport: vec4<f32>,
    // World to the shadow map's clip space (orthographic, along the key light).
    light_view_proj: mat4x4<f32>,
    // Unit vector towards the key light; w: shadow map texel size in world units.
    light_dir: vec4<f32>,
    // Camera position in world space; w unused.
    eye: vec4<f32>,
    // Floor centre (xyz) and the radius at which it has faded out (w).
    floor_center: vec4<f32>,
    // Floor cell size, cells between major lines, half extent, unused.
    floor_grid: vec4<f32>,
    // Floor colours as the target stores them (linear for an sRGB target,
    // sRGB-encoded for a plain unorm one): minor lines, major lines, the floor.
    floor_minor: vec4<f32>,
    floor_major: vec4<f32>,
    floor_color: vec4<f32>,
    // The part of the floor its shadow is drawn over (where a lookup can
    // find a caster, see shadow.rs): min x, min z, max x, max z.
    shadow_rect: vec4<f32>,
    // x: the least coverage of a pixel an outline draws: 0 where outlines are
    // filtered (coverage becomes samples on a multisampled target, and is
    // blended at full quality on one sample), 0.5 in the fast look (a pixel is
    // drawn when its centre is covered); yzw unused.
    samples: vec4<f32>,
    // Rows z and w of projection × view: a world point's clip-space depth
    // and w in two dot products (the capsule shader needs them at every pixel).
    clip_z: vec4<f32>,
    clip_w: vec4<f32>,
    // The view's six planes in view space (unit normal towards the inside,
    // offset): a point p is inside where dot(n.xyz, p) + n.w >= 0 for each.
    view_planes: array<vec4<f32>, 6>,
};

@group(0) @binding(0) var<uniform> frame: Frame;

// Whether the target is a plain unorm one, whose colours the shaders encode
// (see `to_target`). A pipeline constant, not a uniform, so that pipelines for
// sRGB targets hold no encoding: software rasterisers run both sides of a branch.
override ENCODE_SRGB: bool = false;

// Whether lines' and spheres' outlines are filtered by their coverage and
// blended over what is behind them (one sample at full quality: the renderer
// draws them farthest first); else they are hard, and a multisampled target's
// samples smooth the lines. A pipeline constant like ENCODE_SRGB.
override BLEND_OUTLINES: bool = false;

// How much of a pixel an outline covers when the pixel's centre is
// `outside_px` pixels outside it (negative: inside): a one-pixel-wide ramp,
// the edge filter of capsules and spheres.
fn outline_coverage(outside_px: f32) -> f32 {
    return clamp(0.5 - outside_px, 0.0, 1.0);
}

// Linear colour to what the target stores: sRGB targets encode in hardware,
// plain unorm targets (egui's, which composites in gamma space) here.
fn to_target(c: vec4<f32>) -> vec4<f32> {
    if (!ENCODE_SRGB) {
        return c;
    }
    let lo = c.rgb * 12.92;
    let hi = 1.055 * pow(max(c.rgb, vec3<f32>(0.0)), vec3<f32>(1.0 / 2.4)) - 0.055;
    return vec4<f32>(select(hi, lo, c.rgb <= vec3<f32>(0.0031308)), c.a);
}

// How far behind the floor the fast look's shadow footprints mark its depth, in
// normalized depth (capsule.wgsl's `vs_footprint`); the quad that darkens the
// marked pixels lies half as far behind, so its depth test tells them from the
// floor by far more than the rounding between triangles of one plane, and the
// figures drawn after them are not hidden by the marks.
const MARK_DEPTH: f32 = 4e-6;

// Opacity of the floor at `p`: 1 near the centre, fading out towards the edge.
fn floor_alpha(p: vec3<f32>) -> f32 {
    let r = length(p.xz - frame.floor_center.xz) / max(frame.floor_center.w, 1e-6);
    return 1.0 - smoothstep(0.45, 1.0, r);
}

// How much a floor shadow at `p` darkens the floor: the factor the colour
// below is multiplied by where the key light is `lit` (0 in full shadow).
fn floor_shadow_factor(p: vec3<f32>, lit: f32) -> f32 {
    return 1.0 - (1.0 - lit) * 0.55 * floor_alpha(p) * frame.floor_color.a;
}
