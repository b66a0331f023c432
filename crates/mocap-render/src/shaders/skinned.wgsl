// Skinned meshes (bodies): every vertex is moved by up to four joint matrices,
// blended by its weights (linear-blend skinning). The matrices of every draw of
// the frame live in one RGBA32F texture, three texels per matrix (the rows of its
// affine 3×4 part), MATRICES_PER_ROW per row, read with textureLoad (WebGL2 has no
// storage buffers in vertex shaders; textures work everywhere). Influences of
// weight 0 are skipped. Each draw's instance gives the
// index of its first matrix, its tint and whether to show the weights instead.
// `Frame`, `frame`, `to_target` and `shade` come from frame.wgsl and lighting.wgsl.

const MATRICES_PER_ROW: u32 = 256u;

@group(2) @binding(0) var joint_matrices: texture_2d<f32>;
// The mesh's colour texture (1×1 white without one); not bound in the shadow pass.
@group(3) @binding(0) var surface_texture: texture_2d<f32>;
@group(3) @binding(1) var surface_sampler: sampler;

struct SkinnedVertex {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) joints: vec4<u32>,
    @location(3) weights: vec4<f32>,
    // Instance: first matrix of this draw (x); linear tint (rgb) and 1 for the weights view (w).
    @location(4) base: vec4<u32>,
    @location(5) tint_mode: vec4<f32>,
    // The vertex's own sRGB colour (white for a generated body).
    @location(6) color: vec4<f32>,
    // Texture coordinate (xy) and 1 where the texture colours the vertex (z).
    @location(7) tex: vec4<f32>,
};

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec3<f32>,
    @location(3) tex: vec3<f32>,
};

// The rows of a joint's matrix (affine: the fourth row is 0 0 0 1), weighted.
struct Rows {
    r0: vec4<f32>,
    r1: vec4<f32>,
    r2: vec4<f32>,
};

fn add_joint(acc: Rows, index: u32, w: f32) -> Rows {
    let x = i32((index % MATRICES_PER_ROW) * 3u);
    let y = i32(index / MATRICES_PER_ROW);
    var out: Rows;
    out.r0 = acc.r0 + textureLoad(joint_matrices, vec2<i32>(x, y), 0) * w;
    out.r1 = acc.r1 + textureLoad(joint_matrices, vec2<i32>(x + 1, y), 0) * w;
    out.r2 = acc.r2 + textureLoad(joint_matrices, vec2<i32>(x + 2, y), 0) * w;
    return out;
}

// The blended matrix of a vertex, as rows.
fn skin_rows(v: SkinnedVertex) -> Rows {
    let b = v.base.x;
    var m = add_joint(Rows(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0)), b + v.joints.x, v.weights.x);
    if (v.weights.y > 0.0) {
        m = add_joint(m, b + v.joints.y, v.weights.y);
    }
    if (v.weights.z > 0.0) {
        m = add_joint(m, b + v.joints.z, v.weights.z);
    }
    if (v.weights.w > 0.0) {
        m = add_joint(m, b + v.joints.w, v.weights.w);
    }
    return m;
}

fn skin_point(m: Rows, p: vec3<f32>) -> vec3<f32> {
    let h = vec4<f32>(p, 1.0);
    return vec3<f32>(dot(m.r0, h), dot(m.r1, h), dot(m.r2, h));
}

fn skin_vector(m: Rows, n: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(m.r0.xyz, n), dot(m.r1.xyz, n), dot(m.r2.xyz, n));
}

// A colour per joint (golden-ratio hues), for the weights view.
fn joint_color(j: u32) -> vec3<f32> {
    let h = fract(f32(j) * 0.61803398875) * 6.0;
    let k = vec3<f32>(5.0, 3.0, 1.0);
    let c = clamp(abs(fract((h + k) / 6.0) * 6.0 - 3.0) - 1.0, vec3<f32>(0.0), vec3<f32>(1.0));
    return mix(vec3<f32>(0.15), c, 0.85);
}

@vertex
fn vs_main(v: SkinnedVertex) -> Out {
    let m = skin_rows(v);
    let world = skin_point(m, v.position);
    var out: Out;
    out.position = frame.projection * frame.view * vec4<f32>(world, 1.0);
    out.world = world;
    out.normal = skin_vector(m, v.normal);
    // The weights view shows no texture.
    out.tex = vec3<f32>(v.tex.xy, select(v.tex.z, 0.0, v.tint_mode.w > 0.5));
    if (v.tint_mode.w > 0.5) {
        out.color = joint_color(v.joints.x) * v.weights.x + joint_color(v.joints.y) * v.weights.y
            + joint_color(v.joints.z) * v.weights.z + joint_color(v.joints.w) * v.weights.w;
    } else {
        // sRGB to linear (the tint is linear already).
        let c = v.color.rgb;
        let linear = select(pow((c + 0.055) / 1.055, vec3<f32>(2.4)), c / 12.92, c <= vec3<f32>(0.04045));
        out.color = v.tint_mode.rgb * linear;
    }
    return out;
}

// Depth-only pass into the shadow map.
@vertex
fn vs_shadow(v: SkinnedVertex) -> @builtin(position) vec4<f32> {
    return frame.light_view_proj * vec4<f32>(skin_point(skin_rows(v), v.position), 1.0);
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    // Sampled in uniform control flow; used where the vertex is textured.
    let texel = textureSample(surface_texture, surface_sampler, in.tex.xy).rgb;
    let color = select(in.color, in.color * texel, in.tex.z > 0.5);
    var n = normalize(in.normal);
    if (dot(n, frame.eye.xyz - in.world) < 0.0) {
        n = -n;
    }
    return to_target(vec4<f32>(shade(color, in.world, n), 1.0));
}
