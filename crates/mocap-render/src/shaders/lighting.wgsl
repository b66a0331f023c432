// Lighting shared by the lit pipelines (capsules, spheres, floor): a key light
// with a soft shadow from the shadow map, and sky/ground ambient.
// `Frame`, `frame` and `to_target` come from frame.wgsl.

// The fast look (see `SceneRenderer::fast_look`): one shadow lookup per pixel
// instead of four. A pipeline constant, not a uniform, so that each pipeline
// holds only its own path: software rasterisers run both sides of a branch.
override FAST_LOOK: bool = false;

// Whether the frame has shadows; without them no pixel looks at the shadow
// map (a pipeline constant for the same reason as FAST_LOOK).
override SHADOWS: bool = true;

@group(1) @binding(0) var shadow_map: texture_depth_2d;
@group(1) @binding(1) var shadow_sampler: sampler_comparison;

const SKY: vec3<f32> = vec3<f32>(0.50, 0.55, 0.65);
const GROUND: vec3<f32> = vec3<f32>(0.22, 0.20, 0.18);
const KEY: vec3<f32> = vec3<f32>(1.0, 0.96, 0.90);

// 1 where the key light reaches `p` (normal `n`), 0 in full shadow; soft at the
// edges (percentage-closer filtering).
fn key_visibility(p: vec3<f32>, n: vec3<f32>) -> f32 {
    if (!SHADOWS || frame.viewport.w <= 0.0) {
        return 1.0;
    }
    let texel = frame.light_dir.w;
    // Normal offset against acne on curved surfaces.
    // The light's projection is orthographic: w is 1, no division.
    let ndc = (frame.light_view_proj * vec4<f32>(p + n * texel * 3.0, 1.0)).xyz;
    // Texture rows run down while clip-space y runs up.
    let uv = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    if (any(uv < vec2<f32>(0.0)) || any(uv > vec2<f32>(1.0)) || ndc.z > 1.0) {
        return 1.0;
    }
    let z = ndc.z - 0.003;
    // The fast look: one hardware-filtered (2x2 bilinear) comparison.
    if (FAST_LOOK) {
        return mix(1.0, textureSampleCompareLevel(shadow_map, shadow_sampler, uv, z), frame.viewport.w);
    }
    // Four hardware-filtered comparisons 1.5 texels apart: a soft edge about
    // four texels wide for four taps.
    let d = 0.75 / vec2<f32>(textureDimensions(shadow_map));
    let lit = textureSampleCompareLevel(shadow_map, shadow_sampler, uv + vec2<f32>(-d.x, -d.y), z)
        + textureSampleCompareLevel(shadow_map, shadow_sampler, uv + vec2<f32>(d.x, -d.y), z)
        + textureSampleCompareLevel(shadow_map, shadow_sampler, uv + vec2<f32>(-d.x, d.y), z)
        + textureSampleCompareLevel(shadow_map, shadow_sampler, uv + vec2<f32>(d.x, d.y), z);
    let v = lit * 0.25;
    return mix(1.0, v, frame.viewport.w);
}

// Shades a surface of linear colour `base` at `p` with unit normal `n`.
fn shade(base: vec3<f32>, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return shade_seen(base, p, n, normalize(frame.eye.xyz - p));
}

// `shade`, where the unit vector `v` from `p` towards the eye is known (a
// ray-cast impostor's: its ray reversed).
fn shade_seen(base: vec3<f32>, p: vec3<f32>, n: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let l = frame.light_dir.xyz;
    let visible = key_visibility(p, n);
    let diffuse = max(dot(n, l), 0.0) * visible;
    let ambient = mix(GROUND, SKY, n.y * 0.5 + 0.5);
    let h = normalize(l + v);
    // The 40th power by squaring (x^32 x^8): a software rasteriser computes
    // `pow` as an exponential of a logarithm, several times the work.
    let x2 = max(dot(n, h), 0.0) * max(dot(n, h), 0.0);
    let x8 = x2 * x2 * x2 * x2;
    let x32 = x8 * x8 * x8 * x8;
    let specular = x32 * x8 * 0.25 * visible;
    // Soft rim so silhouettes read against the dark background.
    let edge = 1.0 - max(dot(n, v), 0.0);
    let rim = edge * edge * edge * 0.15;
    return base * (ambient * 0.75 + KEY * diffuse * 0.85) + vec3<f32>(specular + rim * 0.5);
}
