// Vertex-animated meshes (MD2 models): every key frame's positions and normals
// live in one vertex buffer uploaded once; each draw binds two frames (slots 0 and
// 1), the texture coordinates (slot 2) and its instance (slot 3: placement, tint
// and blend factor), and the vertex shader blends the frames. Lit like the
// capsules, textured by the skin (a 1×1 neutral texture without one).
// `Frame`, `frame`, `to_target` and `shade` come from frame.wgsl and lighting.wgsl.

@group(2) @binding(0) var skin: texture_2d<f32>;
@group(2) @binding(1) var skin_sampler: sampler;

struct MorphVertex {
    @location(0) position_a: vec3<f32>,
    @location(1) normal_a: vec3<f32>,
    @location(2) position_b: vec3<f32>,
    @location(3) normal_b: vec3<f32>,
    @location(4) uv: vec2<f32>,
    @location(5) model0: vec4<f32>,
    @location(6) model1: vec4<f32>,
    @location(7) model2: vec4<f32>,
    @location(8) model3: vec4<f32>,
    // Linear tint (rgb) and the weight of frame b (w).
    @location(9) tint_blend: vec4<f32>,
};

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tint: vec3<f32>,
};

fn model_matrix(v: MorphVertex) -> mat4x4<f32> {
    return mat4x4<f32>(v.model0, v.model1, v.model2, v.model3);
}

fn blended_world(v: MorphVertex) -> vec3<f32> {
    let p = mix(v.position_a, v.position_b, v.tint_blend.w);
    return (model_matrix(v) * vec4<f32>(p, 1.0)).xyz;
}

@vertex
fn vs_main(v: MorphVertex) -> Out {
    let world = blended_world(v);
    let m = model_matrix(v);
    let n = mix(v.normal_a, v.normal_b, v.tint_blend.w);
    var out: Out;
    out.position = frame.projection * frame.view * vec4<f32>(world, 1.0);
    out.world = world;
    // Placements are a uniform scale and a translation: normals only turn with the
    // matrix's rotation part.
    out.normal = (m * vec4<f32>(n, 0.0)).xyz;
    out.uv = v.uv;
    out.tint = v.tint_blend.rgb;
    return out;
}

// Depth-only pass into the shadow map.
@vertex
fn vs_shadow(v: MorphVertex) -> @builtin(position) vec4<f32> {
    return frame.light_view_proj * vec4<f32>(blended_world(v), 1.0);
}

@fragment
fn fs_main(in: Out, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    var n = normalize(in.normal);
    // Meshes are drawn two-sided (MD2 models are not always closed or consistently
    // wound): light a back face as seen from its own side.
    let to_eye = frame.eye.xyz - in.world;
    if (dot(n, to_eye) < 0.0) {
        n = -n;
    }
    let base = textureSample(skin, skin_sampler, in.uv).rgb * in.tint;
    return to_target(vec4<f32>(shade(base, in.world, n), 1.0));
}
